// actionstring host library — training's exemplars: each label's training
// features summarised by k-means centres (design.md §1.8, exemplars.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/model_data.hpp"

namespace actionstring {
namespace host {

/// Sets the model's exemplar tables from the training characters' features:
/// `features[i]` holds clip i's (feature_dim floats per character, from
/// encode_clip()), `labels[i]` its label. Per label, at most `per_label`
/// centres by k-means (seed `seed` + label; every feature is a centre when a
/// label has no more); exemplar_scale is the training features' mean squared
/// distance to their own label's nearest centre through the runtime's
/// exemplar_distances() (or, when that is 0 because every feature is a centre,
/// to the nearest centre of another label). Features labelled unknown_label
/// (stretches of no action) get at most `per_label` centres of their own
/// (seed + label_count), after every label's; they take no part in the scale.
/// `weight` 0 or `per_label` 0: none. `dims` (1 to feature_dim, 0 = all):
/// the features' leading coordinates the centres are found in and keep
/// (ModelView::exemplar_dim), the rest left out of every distance.
/// Deterministic. Throws std::invalid_argument when a weight is set but no
/// label has a feature, or `dims` exceeds feature_dim.
void set_exemplars(ModelData& m, const std::vector<std::vector<float>>& features, const std::vector<LabelId>& labels,
                   std::size_t per_label, std::size_t dims, double weight, std::uint32_t seed);

}  // namespace host
}  // namespace actionstring
