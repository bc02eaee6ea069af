// actionstring — exemplars: each label's training poses beside the strings in
// clip classification (design.md §1.8).
//
// A character keeps which leaf of the tree a pose fell in and nothing more, so
// two actions that pass through the same key-poses differ only in their order,
// and a pose near a leaf's border is rounded to one side. The exemplars keep
// the continuous feature: per label, a few centres of its training features
// (k-means, in the feature space z the tree's leaves were cut in). A clip is
// compared with each label by the mean, over its characters, of the squared
// distance from the character's feature to the label's nearest centre: the
// frame-level nearest-neighbour vote ("naive-Bayes nearest neighbour"), which
// is blind to order, beside DTW on the strings, which is not.
//
// Per character: exemplar_count × feature_dim multiply-adds, each centre's sum
// in increasing coordinate order (so a generated header, a loaded model and
// every target give the same bits).
#pragma once

#include <cstddef>

#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"

namespace actionstring {

/// Per label, the squared Euclidean distance from one feature to the label's
/// nearest exemplar (+inf for a label without exemplars). Each sum runs over
/// the coordinates in increasing order.
/// @param feature   feature_dim floats (the projected pose the character was
///                  made from, EncodedFrame's previous_feature / current_feature); read only during the call
/// @param distances receives label_count floats (caller-owned)
inline void exemplar_distances(const ModelView& model, const float* feature, float* distances) noexcept {
    if (distances == nullptr) return;
    const std::size_t L = model.label_count, d = model.feature_dim;
    for (std::size_t l = 0; l < L; ++l) distances[l] = detail::infinity();
    if (feature == nullptr || model.exemplars == nullptr || model.exemplar_labels == nullptr) return;
    const float* centre = model.exemplars;
    const std::size_t n = model.exemplar_count;
    auto keep = [&](std::size_t e, float sum) {
        const LabelId label = model.exemplar_labels[e];
        if (label < L && sum < distances[label]) distances[label] = sum;
    };
    // Four centres at a time: four independent chains of additions (one chain
    // waits an add's latency per term), each in its own fixed order, so the
    // sums are the ones a centre-by-centre loop gives.
    std::size_t e = 0;
    for (; e + 4 <= n; e += 4, centre += 4 * d) {
        float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f, s3 = 0.0f;
        for (std::size_t j = 0; j < d; ++j) {
            const float x = feature[j];
            const float d0 = x - centre[j], d1 = x - centre[d + j], d2 = x - centre[2 * d + j],
                        d3 = x - centre[3 * d + j];
            s0 += d0 * d0;
            s1 += d1 * d1;
            s2 += d2 * d2;
            s3 += d3 * d3;
        }
        keep(e, s0);
        keep(e + 1, s1);
        keep(e + 2, s2);
        keep(e + 3, s3);
    }
    for (; e < n; ++e, centre += d) {
        float sum = 0.0f;
        for (std::size_t j = 0; j < d; ++j) {
            const float diff = feature[j] - centre[j];
            sum += diff * diff;
        }
        keep(e, sum);
    }
}

/// What the exemplars add to the distance of each label's representatives,
/// from the per-label sums of exemplar_distances() over a string's
/// `characters` characters:
///   weight · (mean(label) − min over labels of mean) / exemplar_scale,
/// so ≥ 0, and 0 for the label whose exemplars lie nearest. All 0 without
/// exemplars or characters; +inf for a label without exemplars.
/// @param sums      label_count floats; read only during the call
/// @param penalties receives label_count floats (caller-owned); may alias sums
inline void exemplar_penalties(const ModelView& model, const float* sums, std::size_t characters,
                               float* penalties) noexcept {
    if (penalties == nullptr) return;
    const std::size_t L = model.label_count;
    if (!model.has_exemplars() || sums == nullptr || characters == 0) {
        for (std::size_t l = 0; l < L; ++l) penalties[l] = 0.0f;
        return;
    }
    float best = detail::infinity();
    for (std::size_t l = 0; l < L; ++l)
        if (sums[l] < best) best = sums[l];
    if (!detail::is_finite(best)) {  // no label has exemplars, or a sum ran out of range: no opinion
        for (std::size_t l = 0; l < L; ++l) penalties[l] = 0.0f;
        return;
    }
    // Divided once, then multiplied: the same rounding for every label.
    const float scale = model.exemplar_weight / (static_cast<float>(characters) * model.exemplar_scale);
    for (std::size_t l = 0; l < L; ++l) penalties[l] = (sums[l] - best) * scale;
}

}  // namespace actionstring
