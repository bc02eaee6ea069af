// actionstring host library — leave-one-subject-out cross-validation over a
// training list: how settings generalise to a person training never saw,
// without touching a test list.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/clip_list.hpp"
#include "train/options.hpp"

namespace actionstring {
namespace host {

/// One fold: the subject held out and how the model trained without it did.
struct FoldResult {
    std::string subject;
    std::size_t clips = 0;
    double clip_accuracy = 0;
    int representatives = 0;
};

/// Trains once per subject of `clips` on every other subject's clips and
/// measures clip accuracy on the held-out subject's (the model's own method).
/// Folds run in parallel and do not depend on the thread count. Throws
/// std::invalid_argument for fewer than two subjects or a fold that cannot train.
std::vector<FoldResult> cross_validate(const std::vector<LabelledClip>& clips, const TrainingOptions& options);

/// Mean clip accuracy over the folds (each fold weighs the same).
double mean_accuracy(const std::vector<FoldResult>& folds);

}  // namespace host
}  // namespace actionstring
