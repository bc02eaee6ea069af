// actionstring — stage 4: descent of the cluster tree to a character (design.md §1.4).
#pragma once

#include <cstddef>

#include "actionstring/model.hpp"

namespace actionstring {

/// Squared Euclidean distances between a pose feature and two node centroids
/// (a node's children), the metric of the 2-means split that built them.
/// Each sum adds its terms in increasing j; the two run in one loop, so their
/// chains of additions overlap in the pipeline instead of one waiting for the other.
inline void node_distances_sq(const ModelView& model, std::size_t first, std::size_t second, const float* feature,
                              float& to_first, float& to_second) noexcept {
    const std::size_t dim = model.tree_dim();
    const float* a = model.node_centroids + first * dim;
    const float* b = model.node_centroids + second * dim;
    float sum_a = 0.0f, sum_b = 0.0f;
    for (std::size_t j = 0; j < dim; ++j) {
        const float da = feature[j] - a[j], db = feature[j] - b[j];
        sum_a += da * da;
        sum_b += db * db;
    }
    to_first = sum_a;
    to_second = sum_b;
}

/// Descends from the root to a leaf, at each internal node moving to the child
/// whose centroid is nearer (the left child on a tie), and returns the leaf's
/// character. Children always have larger indices than their parent
/// (validate_model checks it), so the loop ends within node_count steps.
/// @param feature tree_dim() floats (a posterior, or the projected pose of a
///                model without a GMM); read only during the call
inline Character descend_tree(const ModelView& model, const float* feature) noexcept {
    std::size_t node = 0;
    for (;;) {
        const int left = model.node_children[2 * node];
        const int right = model.node_children[2 * node + 1];
        if (left < 0) return model.node_characters[node];
        float to_left = 0.0f, to_right = 0.0f;
        node_distances_sq(model, static_cast<std::size_t>(left), static_cast<std::size_t>(right), feature, to_left,
                          to_right);
        node = static_cast<std::size_t>(to_right < to_left ? right : left);
    }
}

}  // namespace actionstring
