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
// Per character: exemplar_count × exemplar_dims() multiply-adds (a model may
// keep only the feature's leading coordinates, ModelView::exemplar_dim), each centre's sum
// in one fixed order (detail::exemplar_distance()), so a generated header, a
// loaded model, the lanes of an x86 host and a Cortex-M4 give the same bits.
#pragma once

#include <cstddef>

#include "actionstring/detail/lanes.hpp"
#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"

namespace actionstring {

namespace detail {

/// The squared distance from x to one centre, summed as every target sums it:
/// four partial sums, sum k over the coordinates j ≡ k (mod 4) in increasing j,
/// then (sum0 + sum1) + (sum2 + sum3). Four chains because four lanes take a
/// block of four coordinates per step (exemplar_distances()); the scalar loop
/// keeps the same order, so a lane target, a Cortex-M4 and the trainer agree.
inline float exemplar_distance(const float* x, const float* centre, std::size_t d) noexcept {
    float sum0 = 0.0f, sum1 = 0.0f, sum2 = 0.0f, sum3 = 0.0f;
    std::size_t j = 0;
    for (; j + 4 <= d; j += 4) {
        const float d0 = x[j] - centre[j], d1 = x[j + 1] - centre[j + 1], d2 = x[j + 2] - centre[j + 2],
                    d3 = x[j + 3] - centre[j + 3];
        sum0 += d0 * d0;
        sum1 += d1 * d1;
        sum2 += d2 * d2;
        sum3 += d3 * d3;
    }
    // The last d mod 4 coordinates, each to its own chain.
    if (j < d) {
        const float d0 = x[j] - centre[j];
        sum0 += d0 * d0;
    }
    if (j + 1 < d) {
        const float d1 = x[j + 1] - centre[j + 1];
        sum1 += d1 * d1;
    }
    if (j + 2 < d) {
        const float d2 = x[j + 2] - centre[j + 2];
        sum2 += d2 * d2;
    }
    return (sum0 + sum1) + (sum2 + sum3);
}

/// Where centre e's distance goes: its label's nearest so far, `no_action`
/// for a centre of "no action" when the caller asked for it, else nowhere (null).
inline float* nearest_slot(const ModelView& model, std::size_t e, float* distances, float* no_action) noexcept {
    const LabelId label = model.exemplar_labels[e];
    return label < model.label_count ? distances + label : (label == unknown_label ? no_action : nullptr);
}

/// The nearest distance of a run of centres that share a slot (a label's
/// centres are stored together), kept in a register and written to the slot
/// once when the run ends, rather than read and written back per centre,
/// which chains every centre to the last through memory. Each step is
/// `distance < nearest ? distance : nearest` (a select, not a jump: which
/// centre is nearer depends on the data), as it was per centre, and a minimum
/// does not depend on the grouping: the same bits.
struct NearestRun {
    float* slot = nullptr;
    float nearest = infinity();

    void take(float* to, float distance) noexcept {
        if (to != slot) {
            flush();
            slot = to;
            nearest = to != nullptr ? *to : infinity();
        }
        nearest = distance < nearest ? distance : nearest;
    }
    void flush() noexcept {
        if (slot != nullptr) *slot = nearest;
        slot = nullptr;
    }
};

}  // namespace detail

/// The nearest-so-far update of exemplar_distances() for centres
/// [first, last) only: `distances` (and `no_action`, when not null) already
/// hold the nearest distances of the centres before, or +inf. Taking the
/// centres in several calls gives the same bits as one call (each centre's sum
/// is fixed, and a minimum does not depend on the order), so a device can
/// spread the work over frames (AnnotatorConfig::spread_work).
inline void nearest_exemplars(const ModelView& model, const float* feature, std::size_t first, std::size_t last,
                              float* distances, float* no_action = nullptr) noexcept {
    if (distances == nullptr || feature == nullptr || model.exemplars == nullptr || model.exemplar_labels == nullptr)
        return;
    const std::size_t d = model.exemplar_dims();
    const std::size_t n = last < model.exemplar_count ? last : model.exemplar_count;
    std::size_t e = first;
    const float* centre = model.exemplars + e * d;
    detail::NearestRun run;
#if ACTIONSTRING_DETAIL_LANES == 4
    // Four centres at a time, each in its own register of four partial sums
    // (lane k: the coordinates j ≡ k mod 4), so the four chains of additions are
    // independent; then a transpose puts each partial sum of the four centres
    // in one register, and (sum0 + sum1) + (sum2 + sum3) finishes all four at
    // once. The last d mod 4 coordinates enter padded with zeros, which add
    // exactly nothing (0 − 0 squared is +0, and a sum of squares is never −0).
    const std::size_t body = d & ~static_cast<std::size_t>(3), tail = d - body;
    float padded[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (std::size_t j = 0; j < tail; ++j) padded[j] = feature[body + j];
    const detail::Lanes x_tail = detail::load_lanes(padded);
    for (; e + 4 <= n; e += 4, centre += 4 * d) {
        detail::Lanes sums[4] = {detail::broadcast(0.0f), detail::broadcast(0.0f), detail::broadcast(0.0f),
                                 detail::broadcast(0.0f)};
        for (std::size_t j = 0; j < body; j += 4) {
            const detail::Lanes x = detail::load_lanes(feature + j);
            for (std::size_t k = 0; k < 4; ++k) {
                const detail::Lanes diff = x - detail::load_lanes(centre + k * d + j);
                sums[k] = sums[k] + diff * diff;
            }
        }
        if (tail != 0) {
            for (std::size_t k = 0; k < 4; ++k) {
                float c[4] = {0.0f, 0.0f, 0.0f, 0.0f};
                for (std::size_t j = 0; j < tail; ++j) c[j] = centre[k * d + body + j];
                const detail::Lanes diff = x_tail - detail::load_lanes(c);
                sums[k] = sums[k] + diff * diff;
            }
        }
        detail::transpose(sums[0], sums[1], sums[2], sums[3]);
        float four[4];
        detail::store_lanes(four, (sums[0] + sums[1]) + (sums[2] + sums[3]));
        const LabelId* label = model.exemplar_labels + e;
        if (label[0] == label[1] && label[0] == label[2] && label[0] == label[3]) {
            // Four centres of one label, the usual case: one slot.
            float* const slot = detail::nearest_slot(model, e, distances, no_action);
            for (std::size_t k = 0; k < 4; ++k) run.take(slot, four[k]);
        } else {
            for (std::size_t k = 0; k < 4; ++k)
                run.take(detail::nearest_slot(model, e + k, distances, no_action), four[k]);
        }
    }
#endif
    for (; e < n; ++e, centre += d)
        run.take(detail::nearest_slot(model, e, distances, no_action), detail::exemplar_distance(feature, centre, d));
    run.flush();
}

/// Per label, the squared Euclidean distance from one feature to the label's
/// nearest exemplar (+inf for a label without exemplars). Each centre's sum
/// is detail::exemplar_distance()'s, in its order, on every target.
/// @param feature   feature_dim floats, of which the first exemplar_dims() are read (the projected pose the character was
///                  made from, EncodedFrame's previous_feature / current_feature); read only during the call
/// @param distances receives label_count floats (caller-owned)
/// @param no_action when not null, receives the distance to the nearest centre
///                  of "no action" (ModelView::has_no_action_exemplars(); +inf without)
inline void exemplar_distances(const ModelView& model, const float* feature, float* distances,
                               float* no_action = nullptr) noexcept {
    if (distances == nullptr) return;
    for (std::size_t l = 0; l < model.label_count; ++l) distances[l] = detail::infinity();
    if (no_action != nullptr) *no_action = detail::infinity();
    nearest_exemplars(model, feature, 0, model.exemplar_count, distances, no_action);
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
