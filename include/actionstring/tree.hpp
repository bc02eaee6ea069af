// actionstring — stage 4: descent of the cluster tree to a character (design.md §1.4).
#pragma once

#include <cstddef>

#include "actionstring/model.hpp"

namespace actionstring {

/// Squared Euclidean distance between a pose feature and a node centroid,
/// the metric of the 2-means split that built the node.
inline float node_distance_sq(const ModelView& model, std::size_t node, const float* feature) noexcept {
    const std::size_t dim = model.tree_dim();
    const float* centroid = model.node_centroids + node * dim;
    float sum = 0.0f;
    for (std::size_t j = 0; j < dim; ++j) {
        const float diff = feature[j] - centroid[j];
        sum += diff * diff;
    }
    return sum;
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
        const float to_left = node_distance_sq(model, static_cast<std::size_t>(left), feature);
        const float to_right = node_distance_sq(model, static_cast<std::size_t>(right), feature);
        node = static_cast<std::size_t>(to_right < to_left ? right : left);
    }
}

}  // namespace actionstring
