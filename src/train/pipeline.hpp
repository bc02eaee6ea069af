// actionstring host library — training: every table of a model from labelled
// clips (design §1), as a sequence of stages.
#pragma once

#include <vector>

#include "io/clip_list.hpp"
#include "model/model_data.hpp"
#include "train/options.hpp"

namespace actionstring {
namespace host {

/// Trains every table of a model from labelled clips (all on one skeleton).
/// The runtime's own code normalises, projects, computes posteriors,
/// descends the tree, samples strings and measures string distances.
/// Throws std::invalid_argument with a clear message on unusable input.
/// `no_action`, when given, holds stretches of motion that are no action (the
/// unlabelled parts of training recordings, unlabelled_stretches()): with
/// votes on, the model learns log P(c | no action) from them, which the
/// segmenter uses to say "no action" (its unknown path).
ModelData train_model(const std::vector<LabelledClip>& clips, const TrainingOptions& options,
                      TrainingReport* report = nullptr, const std::vector<LabelledClip>* no_action = nullptr);

}  // namespace host
}  // namespace actionstring
