// actionstring host library — training's clip descriptors: linear classifiers
// over each training clip's temporal pyramid of feature means and covariances,
// and over its motion directions, fitted by ridge regression (design.md §1.8,
// descriptor.hpp).
#pragma once

#include <cstddef>
#include <vector>

#include "model/model_data.hpp"

namespace actionstring {
namespace host {

/// Sets the model's clip descriptor from the training clips' features:
/// `features[i]` holds clip i's (feature_dim floats per character, from
/// encode_clip()), `labels[i]` its label (clips labelled unknown_label are
/// left out). Each clip's descriptor is the runtime's clip_descriptor() over
/// `levels` levels and the features' first `dims` coordinates (0 = all, at
/// most max_descriptor_dims); every coordinate is standardised over the
/// clips, and one ridge regression per label (target +1 for its clips, −1
/// for the others, an unpenalised intercept, penalty `ridge` on the squared
/// weights) gives its scores. The standardisation is folded into the stored
/// weights and bias. `levels` 0 or `weight` 0: none. Deterministic.
/// Throws std::invalid_argument for dims beyond the feature or 64, levels
/// beyond 8, a non-positive ridge, or fewer than two labelled clips.
void set_descriptor(ModelData& m, const std::vector<std::vector<float>>& features, const std::vector<LabelId>& labels,
                    std::size_t levels, std::size_t dims, double ridge, double weight);

/// Sets the model's motion directions (descriptor.hpp) from the training
/// clips' records: `records[i]` holds clip i's (direction_record_floats()
/// per character, from encode_clip(…, with_records)), `labels[i]` its label
/// (clips labelled unknown_label are left out). Each clip's histograms are the
/// runtime's clip_directions() over `levels` levels; the linear classifier is
/// fitted as set_descriptor()'s, with penalty `ridge`. The model must already
/// hold its pose joints and up axis. `levels` 0 or `weight` 0: none.
/// Deterministic. Throws std::invalid_argument for levels beyond 8, a
/// non-positive ridge, a model without pose joints, or fewer than two
/// labelled clips.
void set_directions(ModelData& m, const std::vector<std::vector<float>>& records, const std::vector<LabelId>& labels,
                    std::size_t levels, double ridge, double weight);

/// Sets the model's window directions (descriptor.hpp,
/// window_direction_penalties()) from the training clips' records (as
/// set_directions() takes them): every character t ≥ 1 of every labelled
/// clip gives a sample, clip_directions() over one level of the window of
/// `chars` records ending at t (fewer at the clip's start, as at a stream's),
/// labelled with its clip's label; the linear classifier is fitted as
/// set_descriptor()'s, with penalty `ridge`. Long lists take every k-th
/// window (at most about 20,000). The model must already hold its pose joints
/// and up axis. `chars` 0: none. Deterministic. Throws std::invalid_argument
/// for a window of 1 or beyond 1024 characters, a non-positive ridge, a model
/// without pose joints, or fewer than two labelled samples.
void set_window_directions(ModelData& m, const std::vector<std::vector<float>>& records,
                           const std::vector<LabelId>& labels, std::size_t chars, double ridge);

}  // namespace host
}  // namespace actionstring
