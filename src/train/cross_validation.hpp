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

/// One fold: the subject(s) held out and how the model trained without them did.
struct FoldResult {
    std::string subject;  ///< "s01", or "s01+s06" when a fold holds out several
    std::size_t clips = 0;
    double clip_accuracy = 0;
    int representatives = 0;
    double margin = 0;  ///< Mean signed margin of the held-out clips (ClipScore).
};

/// The subjects of `clips` in folds: one fold per subject, or with more
/// subjects than `max_folds` (> 0) that many folds, the sorted subjects dealt
/// round-robin (fold k holds subjects k, k + max_folds, …). Deterministic.
std::vector<std::vector<std::string>> subject_folds(const std::vector<LabelledClip>& clips, std::size_t max_folds = 0);

/// Self-tuning's folds: at most this many, so its time stops growing with the
/// number of people in a list (every list in ../shared/data has at most five
/// training subjects, so there it is still leave-one-subject-out).
constexpr std::size_t tuning_max_folds = 5;

/// Trains once per fold of subject_folds(clips, max_folds) on the other folds'
/// clips and measures clip accuracy on the held-out clips (the model's own
/// method). Folds run in parallel and do not depend on the thread count.
/// Throws std::invalid_argument for fewer than two subjects or a fold that cannot train.
std::vector<FoldResult> cross_validate(const std::vector<LabelledClip>& clips, const TrainingOptions& options,
                                       std::size_t max_folds = 0);

/// Mean clip accuracy over the folds (each fold weighs the same).
double mean_accuracy(const std::vector<FoldResult>& folds);

/// Mean signed margin over the folds (each fold weighs the same).
double mean_margin(const std::vector<FoldResult>& folds);

}  // namespace host
}  // namespace actionstring
