// actionstring host library — each label's rejection bound, learned at
// training from held-out positives and negatives (design.md §1.8).
//
// A clip or window is labelled by its nearest representatives; a label whose
// nearest representative is further than that label's bound becomes unknown
// (classify_distances()). The bound of label l is chosen where the training
// data shows what l's own clips reach and what is not l but lands on l:
//
// - positives: every training clip, classified with the representatives made
//   from its own subject's clips left out (a new person, as at test time; with
//   one subject in the list, only the one made from the clip itself);
// - negatives: what lands on l but is not l — synthetic strings (the first
//   half of one clip joined to the second half of a clip of another label;
//   each clip at twice and at half its speed, when it lands on another label
//   than its own), training clips misclassified as l, and, from recordings,
//   the unlabelled stretches (no action). Synthetic strings leave out their
//   source subjects' representatives too, so both sides are measured alike.
//
// Among bounds that keep at least `keep` of l's positives, the one that keeps
// the most positives plus rejects the most negatives (Youden's J) wins; the
// bound sits halfway to the next distance above it. A label with no positive
// or no negative gets no bound (infinity): there is nothing to learn it from.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <functional>
#include <vector>

#include "actionstring/model.hpp"

namespace actionstring {
namespace host {

/// What the bound of one label was learned from, and what it does on them.
struct LabelBoundReport {
    std::size_t positives = 0, negatives = 0;
    float bound = 0.0f;               ///< infinity: none
    double positives_kept = 1.0;      ///< Fraction of the positives within the bound.
    double negatives_rejected = 0.0;  ///< Fraction of the negatives beyond it.
};

/// With exemplars (exemplars.hpp): each character's distances to every
/// label's nearest centre, label_count floats per character, so that a
/// synthetic negative splices and warps them with its characters. Training
/// measures a clip's rows with centres fitted without its subject's clips (as
/// the representatives it is compared with leave them out).
struct ExemplarRows {
    std::vector<std::vector<float>> strings;    ///< per training string: its length × label_count floats
    std::vector<std::vector<float>> no_action;  ///< per string of no action, likewise
};

/// With a clip descriptor (descriptor.hpp): each string's features, so that a
/// synthetic negative splices and warps them with its characters, and what
/// measures a sample's descriptor penalties. Training fits the descriptor
/// without the subjects a sample was made from (as the representatives it is
/// compared with leave them out).
struct DescriptorSamples {
    std::vector<std::vector<float>> strings;    ///< per training string: its descriptor_rows(), `width` per character
    std::vector<std::vector<float>> no_action;  ///< per string of no action, likewise
    std::size_t width = 0;                      ///< descriptor_row_width()
    /// label_count penalties of `features`, made from training strings `first`
    /// and `second` (the same for one string's), fitted without their subjects.
    std::function<std::vector<float>(const std::vector<float>& features, std::size_t first, std::size_t second)>
        of_strings;
    /// The same for stretch `stretch` of no action, fitted without its subject.
    std::function<std::vector<float>(const std::vector<float>& features, std::size_t stretch)> of_stretch;
};

/// Learns label_count bounds for `model` (complete but for the bounds; its own
/// has_label_bounds is ignored). `strings[i]` is training clip i's string,
/// `labels[i]` its label, `subjects[i]` its performer, `own_representative[i]`
/// the representative made from it (or −1); `no_action` holds strings of
/// stretches that are no action (may be empty). `keep` in (0, 1]. With
/// `rows` (a model with exemplars), each sample's summed rows join its
/// classification as the exemplars' penalties, as classify_clip() does; with
/// `descriptor` (a model with a clip descriptor), its descriptor's penalties do too.
/// Deterministic for a seed, on any number of cores.
std::vector<float> learn_label_bounds(const ModelView& model, const std::vector<std::vector<Character>>& strings,
                                      const std::vector<LabelId>& labels, const std::vector<std::string>& subjects,
                                      const std::vector<long>& own_representative,
                                      const std::vector<std::vector<Character>>& no_action, double keep,
                                      std::uint32_t seed, std::vector<LabelBoundReport>* report = nullptr,
                                      const ExemplarRows* rows = nullptr,
                                      const DescriptorSamples* descriptor = nullptr);

/// Floats that belong to each character of each string, to be cut and
/// repeated with the characters: `(*rows)[i]` holds `width` floats per
/// character of string i (its exemplar distances, or its features).
struct PerCharacterRows {
    const std::vector<std::vector<float>>* rows = nullptr;
    std::size_t width = 0;
};

/// A synthetic string that is no performance of a label: a spliced pair of
/// halves (`own` unknown_label: no label fits it), or a clip at twice or half
/// its speed (`own` its label: landing there, it is still that action, so it
/// counts as a negative only against the others).
struct SyntheticNegative {
    std::vector<Character> string;
    /// One per PerCharacterRows given, in order: its rows cut and repeated as
    /// the characters were, so `rows[k]` has that set's width per character.
    std::vector<std::vector<float>> rows;
    LabelId own = unknown_label;
    std::size_t first = 0, second = 0;  ///< The strings it was made from (the same one when warped).
};

/// The synthetic negatives of `strings` (labels[i] is string i's): per string
/// of two characters or more, its first half joined to the second half of a
/// string of another label (picked by a generator seeded with `seed`), then
/// the string sped up (every other character) and slowed down (each twice).
/// Each of `per_character` is cut and repeated with the characters.
/// Throws std::invalid_argument when a row set does not match the strings.
std::vector<SyntheticNegative> synthetic_negatives(const std::vector<std::vector<Character>>& strings,
                                                   const std::vector<LabelId>& labels, std::uint32_t seed,
                                                   const std::vector<PerCharacterRows>& per_character = {});

/// The bound for one label's positive and negative distances (the rule above).
float choose_label_bound(std::vector<float> positives, std::vector<float> negatives, double keep);

}  // namespace host
}  // namespace actionstring
