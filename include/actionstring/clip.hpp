// actionstring — a whole clip's label (design.md §1.8): a gesture between two
// events of the game or the device, or a recorded take, whose bounds the
// caller knows.
//
// The streaming annotator explains a running stream as actions laid end to
// end; a clip whose beginning and end are known is classified as a whole
// instead, as the trainer's cross-validation and `eval` classify clips: the
// batch string distance to every representative, plus what the characters'
// votes, the exemplars and the clip descriptor add per label, then the kNN of
// classify_distances(). The caller collects the clip's characters (and, when
// the model has exemplars or a clip descriptor, the features they were made
// from: EncodedFrame's previous_feature / current_feature) from a
// StringEncoder, in order; the functions here compose the stages in the order
// the host's classify_clip() does, which calls them, so a device and `eval`
// give a clip the same label bit for bit.
//
// Nothing is allocated: the scratch is the caller's, clip_scratch_floats()
// floats and clip_cells() DTW cells, read and written only during a call.
#pragma once

#include <cstddef>
#include <cstdint>

#include "actionstring/classify.hpp"
#include "actionstring/descriptor.hpp"
#include "actionstring/exemplars.hpp"
#include "actionstring/model.hpp"
#include "actionstring/string_distance.hpp"

namespace actionstring {

/// The longest representative string of a model, in characters.
constexpr std::uint32_t longest_representative(const ModelView& model) noexcept {
    std::uint32_t longest = 0;
    for (std::size_t r = 0; r < model.representative_count; ++r)
        if (model.representative_length(r) > longest) longest = model.representative_length(r);
    return longest;
}

/// DTW cells classify_clip() and representative_distances() need for a clip of
/// `length` characters (one representative at a time).
constexpr std::size_t clip_cells(const ModelView& model, std::size_t length) noexcept {
    return string_distance_cells(length, longest_representative(model));
}

/// Floats of scratch classify_clip() needs: the distance to every
/// representative, four label-sized rows (the exemplars' sums, their
/// penalties, the descriptor's penalties, all of them added) and the clip
/// descriptor's scratch.
constexpr std::size_t clip_scratch_floats(const ModelView& model) noexcept {
    return model.representative_count + 4u * model.label_count + model.descriptor_size();
}

/// The batch string distance (the model's variant and normalisation) from a
/// clip's string to every representative; +inf for a representative it
/// cannot be compared with (an empty string, a string too long for a path).
/// @param string    `length` characters; read only during the call
/// @param cells     clip_cells(model, length) cells (caller-owned), overwritten
/// @param distances receives representative_count floats (caller-owned)
inline void representative_distances(const ModelView& model, const Character* string, std::size_t length,
                                     detail::Cell* cells, float* distances) noexcept {
    if (distances == nullptr) return;
    for (std::size_t r = 0; r < model.representative_count; ++r) {
        distances[r] = detail::infinity();
        if (string == nullptr || length == 0 || cells == nullptr) continue;
        const Character* rep = model.representative_chars + model.representative_offsets[r];
        // A refusal leaves the distance at +inf.
        (void)string_distance(string, length, rep, model.representative_length(r), character_weights(model),
                              MatchOptions{model.variant, model.normalization}, cells, &distances[r]);
    }
}

/// Per label, the sum over a clip's `length` features of exemplar_distances(),
/// in order (what exemplar_penalties() reads). All 0 without exemplars.
/// @param features  length × feature_dim floats; read only during the call
/// @param row       label_count floats of scratch (caller-owned), overwritten
/// @param sums      receives label_count floats (caller-owned)
inline void exemplar_sums(const ModelView& model, const float* features, std::size_t length, float* row,
                          float* sums) noexcept {
    if (sums == nullptr) return;
    const std::size_t L = model.label_count;
    for (std::size_t l = 0; l < L; ++l) sums[l] = 0.0f;
    if (!model.has_exemplars() || features == nullptr || row == nullptr) return;
    for (std::size_t c = 0; c < length; ++c) {
        exemplar_distances(model, features + c * model.feature_dim, row);
        for (std::size_t l = 0; l < L; ++l) sums[l] += row[l];
    }
}

/// What a clip adds to the distance of each label's representatives: the
/// characters' votes, then the exemplars' penalties from their `sums`
/// (exemplar_sums(), or null: none), then the clip descriptor's `descriptor`
/// penalties (descriptor_penalties(), or null: none), added in that order.
/// Returns whether any applies (the model has votes, or exemplars with sums,
/// or a descriptor with penalties); classify_distances() then takes them.
/// @param string     `length` characters; read only during the call
/// @param row        label_count floats of scratch (caller-owned), overwritten
/// @param penalties  receives label_count floats (caller-owned)
inline bool clip_penalties(const ModelView& model, const Character* string, std::size_t length, const float* sums,
                           const float* descriptor, float* row, float* penalties) noexcept {
    if (penalties == nullptr) return false;
    const std::size_t L = model.label_count;
    vote_penalties(model, string, length, penalties);
    const bool exemplars = model.has_exemplars() && sums != nullptr && row != nullptr;
    if (exemplars) {
        exemplar_penalties(model, sums, length, row);
        for (std::size_t l = 0; l < L; ++l) penalties[l] += row[l];
    }
    const bool described = model.has_descriptor() && descriptor != nullptr;
    if (described)
        for (std::size_t l = 0; l < L; ++l) penalties[l] += descriptor[l];
    return model.has_votes() || exemplars || described;
}

/// The label of a whole clip: its string's distance to every representative,
/// what the votes, the exemplars and the clip descriptor add (clip_penalties()),
/// then classify_distances()'s kNN, its unknown distance and bounds.
/// @param string    `length` characters of the clip, in order; read only during the call
/// @param features  length × feature_dim floats, the features those characters
///                  were made from, in order; null to leave out the exemplars
///                  and the clip descriptor (a model without them needs none)
/// @param scratch   clip_scratch_floats(model) floats (caller-owned), overwritten
/// @param cells     clip_cells(model, length) cells (caller-owned), overwritten
/// @return the label (unknown_label for an empty clip, or when nothing is near enough)
inline Classification classify_clip(const ModelView& model, const Character* string, const float* features,
                                    std::size_t length, float* scratch, detail::Cell* cells) noexcept {
    if (scratch == nullptr) return Classification{};
    const std::size_t L = model.label_count;
    float* const distances = scratch;
    float* const sums = distances + model.representative_count;
    float* const row = sums + L;
    float* const described = row + L;
    float* const penalties = described + L;
    float* const descriptor_scratch = penalties + L;
    representative_distances(model, string, length, cells, distances);
    const bool with_descriptor = model.has_descriptor() && features != nullptr;
    const bool with_exemplars = model.has_exemplars() && features != nullptr;
    if (with_descriptor) descriptor_penalties(model, features, length, descriptor_scratch, described);
    if (with_exemplars) exemplar_sums(model, features, length, row, sums);
    const bool any = clip_penalties(model, string, length, with_exemplars ? sums : nullptr,
                                    with_descriptor ? described : nullptr, row, penalties);
    return classify_distances(model, distances, any ? penalties : nullptr);
}

}  // namespace actionstring
