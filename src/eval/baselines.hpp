// actionstring host library — baselines computed by the same tool on the same
// split, beside the model's own clip recognition.
#pragma once

#include <cstdint>
#include <vector>

#include "actionstring/model.hpp"
#include "eval/clip_eval.hpp"
#include "io/clip_list.hpp"

namespace actionstring {
namespace host {

/// Baseline: 1-NN over every training clip's string (no representatives), same
/// model, same distance.
ClipResults evaluate_all_strings(const ModelView& model, const std::vector<LabelledClip>& train,
                                 const std::vector<LabelledClip>& clips);

/// Baseline (paper Fig. 4, "PCA only"): characters from the same top-down
/// 2-means tree, with as many leaves as the model has characters, built on the
/// projected poses instead of GMM posteriors; W is the Euclidean distance
/// between leaf centroids; 1-NN over every training clip's string with the
/// model's string distance. Beside evaluate_all_strings it isolates what the
/// GMM adds.
ClipResults evaluate_pca_characters(const ModelView& model, const std::vector<LabelledClip>& train,
                                    const std::vector<LabelledClip>& clips, std::uint32_t seed = 1);

/// Baseline: classic DTW 1-NN on normalised poses sampled at `rate_hz`
/// (Euclidean frame distance, whole-to-whole boundaries). Uses the model's
/// skeleton roles for normalisation.
ClipResults evaluate_pose_dtw(const ModelView& model, const std::vector<LabelledClip>& train,
                              const std::vector<LabelledClip>& clips, double rate_hz = 15.0);

}  // namespace host
}  // namespace actionstring
