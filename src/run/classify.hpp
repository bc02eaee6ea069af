// actionstring host library — labelling whole strings with the runtime's
// batch string distance and kNN.
#pragma once

#include <vector>

#include "actionstring/classify.hpp"
#include "actionstring/detail/dp.hpp"
#include "actionstring/model.hpp"
#include "actionstring/string_distance.hpp"
#include "io/clip_list.hpp"

namespace actionstring {
namespace host {

/// Label of a whole clip's string: the runtime's batch distance to every
/// representative (the string is the query), plus the characters' label votes
/// when the model has them (vote_penalties()), then the runtime's kNN.
/// `excluded` lists representatives left out of the vote (training measures a
/// clip against those made from other people's clips).
/// `exemplar_sums`, when given, holds label_count floats: exemplar_sums()
/// of the string's features, whose penalties (exemplars.hpp) join the votes.
/// `descriptor`, when given, holds label_count floats: the clip descriptor's
/// penalties of the string's features (clip_descriptor_penalties()), which join them too.
Classification classify_string(const ModelView& model, const std::vector<Character>& string,
                               const std::vector<std::size_t>& excluded = {}, const float* exemplar_sums = nullptr,
                               const float* descriptor = nullptr);

/// The clip descriptors' penalties of a clip: the runtime's
/// descriptor_penalties() of its features (feature_dim floats per character)
/// plus, with motion directions, direction_penalties() of its records
/// (direction_record_floats() per character; ignored without directions):
/// label_count floats, all 0 with neither.
std::vector<float> clip_descriptor_penalties(const ModelView& model, const std::vector<float>& features,
                                             const std::vector<float>& records);

/// What the clip descriptors read of each character, side by side in one row
/// so that rows can be cut, repeated and spliced with the characters (the
/// synthetic negatives of rejection.hpp): the character's feature, then, with
/// motion directions, its record. descriptor_row_width() floats each.
std::size_t descriptor_row_width(const ModelView& model);
std::vector<float> descriptor_rows(const ModelView& model, const std::vector<float>& features,
                                   const std::vector<float>& records);
/// clip_descriptor_penalties() of descriptor_rows().
std::vector<float> descriptor_row_penalties(const ModelView& model, const std::vector<float>& rows);

/// Per label, the sum over `features` (feature_dim floats each) of the
/// runtime's exemplar_distances(): label_count floats, all 0 without exemplars.
std::vector<float> exemplar_sums(const ModelView& model, const std::vector<float>& features);

/// The runtime's exemplar_distances() of each of `features` (feature_dim floats
/// each): label_count floats per feature, in order (empty without exemplars).
/// Rows can be cut and joined with their characters (learned rejection's
/// synthetic negatives) and summed afterwards.
std::vector<float> exemplar_rows(const ModelView& model, const std::vector<float>& features);

/// Per label, the sum of `rows` (label_count floats per character), in order:
/// exemplar_sums() of the features the rows came from, bit for bit.
std::vector<float> sum_exemplar_rows(const std::vector<float>& rows, std::size_t label_count);

/// A clip classified as a model says: its string, and with exemplars or a
/// clip descriptor its features too.
Classification classify_clip(const ModelView& model, const Clip& clip);

/// Each label's score for a clip, as classify_clip() sees it (the runtime's
/// clip_label_distances(): each label's nearest representative, its penalty
/// added; smaller is nearer, +inf where none compares): label_count floats.
std::vector<float> label_distances(const ModelView& model, const Clip& clip);

/// A clip's label and every label's score together, from one encoding and
/// one pass of the runtime's stages: classify_clip()'s Classification and
/// label_distances()'s scores, bit for bit.
struct ScoredClip {
    Classification classification;
    std::vector<float> label_distances;
};
ScoredClip score_clip(const ModelView& model, const Clip& clip);

/// How a model does on labelled clips: the fraction right, and the mean
/// signed margin, a clip's Classification::confidence when it is right and
/// minus it when it is wrong (0 when unknown). The margin tells settings apart
/// where every clip is right (self-tuning at a list's ceiling).
struct ClipScore {
    double accuracy = 0;
    double margin = 0;
};
ClipScore clip_score(const ModelView& model, const std::vector<LabelledClip>& clips);

/// Fraction of clips whose predicted label name equals their label.
double clip_accuracy(const ModelView& model, const std::vector<LabelledClip>& clips);

/// Index of the reference string nearest to `query` by the runtime's string
/// distance (the first on ties), or −1 when none can be compared (an empty
/// string on either side). `workspace` is scratch reused between calls.
long nearest_string(const std::vector<Character>& query, const std::vector<std::vector<Character>>& references,
                    const CharacterWeights& weights, const MatchOptions& options, std::vector<detail::Cell>& workspace);

}  // namespace host
}  // namespace actionstring
