// actionstring host library — training that tunes itself: the settings that
// matter most chosen by leave-one-subject-out cross-validation over the
// training list, never on a test list.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "io/clip_list.hpp"
#include "train/cross_validation.hpp"
#include "train/options.hpp"

namespace actionstring {
namespace host {

/// One setting tried during tuning, and the fold mean it gave.
struct TuningStep {
    std::string setting;  ///< As a config line: "velocity 0.5".
    double mean_accuracy = 0;
    double mean_margin = 0;  ///< The folds' mean signed margin (ClipScore), which breaks ties.
    bool kept = false;       ///< Whether it became the current choice.
};

struct TuningResult {
    TrainingOptions options;        ///< The choice.
    std::vector<TuningStep> steps;  ///< Every setting tried, in order.
    std::vector<FoldResult> folds;  ///< The folds of the choice.
    double seconds = 0;
};

/// Where tuning starts: the settings cross-validation chose on HDM05, MSR
/// Action3D and UTKinect alike (characters on projected poses without a GMM,
/// PCA 24, ε 0.7, σ 0.75, singletons kept; models/README.md).
TrainingOptions tuning_start();

/// Coordinate search from `start`: the velocity weight and span, mirroring,
/// the string rate, ε, σ, the PCA dimension, the votes' weight and the exemplars' (64 per
/// label; not with `reject`), then the exemplars in half the feature's
/// coordinates, one at a time, each value judged by cross_validate()'s fold
/// mean averaged over the seeds seed, seed + 1 and seed + 2, and kept only when
/// strictly higher or, where the fold means tie, when the folds' mean signed
/// margin (ClipScore) is strictly higher: at a list's ceiling every setting
/// scores 1.000, and the margin tells the choices apart (nested
/// cross-validation on HDM05's actors: 188 of 188 held-out clips against 185;
/// models/README.md, "Ties broken by the margin"). The exemplars' dimension,
/// which only saves work, is kept on a tie of the fold means. Deterministic. `folds` are those of the choice at its seed. `progress`, when
/// set, is told each step. The fold mean of the choice is optimistic: it was
/// chosen on those folds.
///
/// Size is not searched: whenever the skeleton has parents the pose is scaled
/// by the torso's length (ScaleMode::torso, when `start` says none). The folds
/// cannot judge size: a list's few subjects are often of one size, and on
/// UTKinect's three adults `none` won by chance and then lost 0.10 of the
/// held-out clips scaled as a child's (models/README.md, "Size on UTKinect").
/// Bone lengths were searched beside it and won the folds by less than a clip
/// while losing online; models/README.md has the measurements.
TuningResult tune_training(const std::vector<LabelledClip>& clips, const TrainingOptions& start,
                           const std::function<void(const TuningStep&)>& progress = {});

/// The settings as 'option value' lines that `actionstring train --config` reads back.
std::string options_as_config(const TrainingOptions& options);

}  // namespace host
}  // namespace actionstring
