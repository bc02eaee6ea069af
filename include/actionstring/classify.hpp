// actionstring — kNN over the representatives (design.md §1.8).
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"

namespace actionstring {

/// Label decided from one set of distances to the representatives.
struct Classification {
    /// Winning label, or unknown_label when its nearest representative is
    /// further than the model's unknown_distance or than the label's own
    /// bound (label_bounds, when the model learned them).
    LabelId label = unknown_label;
    /// The vote's winner even when `label` is unknown (for diagnostics).
    LabelId nearest_label = unknown_label;
    /// Distance to the nearest representative of the winning label.
    float distance = detail::infinity();
    /// Margin in [0, 1]: 1 − distance / (distance to the nearest representative
    /// of any other label); 1 when no other label exists, 0 when unknown or
    /// when another label is at least as close.
    float confidence = 0.0f;
    /// Index of the nearest representative of the winning label.
    std::uint16_t representative = 0xFFFF;
};

/// The characters' label votes for a string (design.md §1.8): per label, what
/// they add to the distance of each of its representatives,
///   λ · (max over labels of m(label) − m(own label)),  m(l) = mean over the
///   string's characters c of log P(c | l),
/// so ≥ 0, and 0 for the label the characters favour most. A character says
/// which actions its key-pose occurs in, wherever it falls in the string; DTW
/// says whether the order matches. All 0 without votes or for an empty string.
/// @param string    `length` characters; read only during the call
/// @param penalties receives label_count floats (caller-owned)
inline void vote_penalties(const ModelView& model, const Character* string, std::size_t length,
                           float* penalties) noexcept {
    if (penalties == nullptr) return;
    const std::size_t L = model.label_count, K = model.character_count;
    for (std::size_t l = 0; l < L; ++l) penalties[l] = 0.0f;
    if (!model.has_votes() || string == nullptr || length == 0) return;
    float best = -detail::infinity();
    for (std::size_t l = 0; l < L; ++l) {
        const float* votes = model.character_votes + l * K;
        float sum = 0.0f;
        for (std::size_t t = 0; t < length; ++t)
            if (string[t] < K) sum += votes[string[t]];
        penalties[l] = sum / static_cast<float>(length);
        if (penalties[l] > best) best = penalties[l];
    }
    for (std::size_t l = 0; l < L; ++l) penalties[l] = model.vote_weight * (best - penalties[l]);
}

/// k-nearest-neighbour vote over representative distances (k = model.neighbours,
/// at most max_neighbours). The label with most votes among the k nearest
/// wins; on a tie, the label of the nearer neighbour. Equal distances keep
/// representative order. Unknown when the winner's distance is not finite
/// (nothing could be compared: an empty string).
/// @param distances representative_count floats; read only during the call
/// @param penalties null, or label_count floats added to the distance of each
///                  label's representatives (vote_penalties()); read only during the call
inline Classification classify_distances(const ModelView& model, const float* distances,
                                         const float* penalties = nullptr) noexcept {
    Classification result;
    const std::size_t R = model.representative_count;
    if (distances == nullptr || R == 0 || model.neighbours > max_neighbours) return result;
    const std::size_t k = model.neighbours < R ? model.neighbours : R;
    auto distance = [&](std::size_t r) {
        return penalties == nullptr ? distances[r] : distances[r] + penalties[model.representative_labels[r]];
    };

    // Insertion into a sorted list of the k nearest: k is small.
    std::uint16_t nearest[max_neighbours] = {};  // (zeroed only to quiet a false maybe-uninitialized)
    std::size_t found = 0;
    for (std::size_t r = 0; r < R; ++r) {
        const float d = distance(r);
        if (detail::is_nan(d)) continue;
        if (found == k && !(d < distance(nearest[k - 1]))) continue;
        std::size_t at = found < k ? found++ : k - 1;
        while (at > 0 && d < distance(nearest[at - 1])) {
            nearest[at] = nearest[at - 1];
            --at;
        }
        nearest[at] = static_cast<std::uint16_t>(r);
    }
    if (found == 0) return result;

    std::size_t best_votes = 0;
    for (std::size_t a = 0; a < found; ++a) {
        const LabelId label = model.representative_labels[nearest[a]];
        std::size_t votes = 0;
        for (std::size_t b = 0; b < found; ++b) votes += model.representative_labels[nearest[b]] == label;
        if (votes > best_votes) {
            best_votes = votes;
            result.nearest_label = label;
            result.representative = nearest[a];
            result.distance = distance(nearest[a]);
        }
    }

    float other = detail::infinity();
    for (std::size_t r = 0; r < R; ++r)
        if (model.representative_labels[r] != result.nearest_label && distance(r) < other) other = distance(r);
    // No representative at a finite distance (an empty clip, strings that
    // cannot be compared): no evidence for any label, so unknown, not the first.
    if (!detail::is_finite(result.distance)) return result;
    if (!(result.distance <= model.unknown_distance)) return result;  // unknown
    if (model.has_label_bounds != 0 && !(result.distance <= model.label_bounds[result.nearest_label]))
        return result;  // unknown: further than this label's positives go
    result.label = result.nearest_label;
    if (!detail::is_finite(other)) result.confidence = 1.0f;
    else if (other > result.distance) result.confidence = (other - result.distance) / other;
    return result;
}

/// Each label's score as classify_distances() sees it: the distance of its
/// nearest representative, with the label's penalty added (+inf for a label
/// whose representatives are all NaN or +inf). For ranking the labels (top-k
/// accuracy, ROC curves, fusion with another classifier): with one neighbour
/// the smallest is the nearest label classify_distances() reports (ties to the
/// first representative); with more, its vote decides. Neither the unknown
/// distance nor the label bounds apply here.
/// @param distances representative_count floats; read only during the call
/// @param penalties null, or label_count floats (as classify_distances()); read only during the call
/// @param out       receives label_count floats (caller-owned)
inline void label_distances(const ModelView& model, const float* distances, const float* penalties,
                            float* out) noexcept {
    if (out == nullptr) return;
    for (std::size_t l = 0; l < model.label_count; ++l) out[l] = detail::infinity();
    if (distances == nullptr) return;
    for (std::size_t r = 0; r < model.representative_count; ++r) {
        const LabelId label = model.representative_labels[r];
        if (label >= model.label_count) continue;
        const float d = penalties == nullptr ? distances[r] : distances[r] + penalties[label];
        if (d < out[label]) out[label] = d;  // false for NaN
    }
}

}  // namespace actionstring
