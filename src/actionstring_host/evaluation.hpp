// actionstring host library — evaluation of clip recognition, with baselines.
#pragma once

#include <string>
#include <vector>

#include "actionstring/model.hpp"
#include "actionstring_host/training.hpp"

namespace actionstring {
namespace host {

/// Clip-recognition results of one method on one list.
struct ClipResults {
    std::string method;
    std::vector<std::string> labels;               ///< Row and column names of the confusion matrix.
    std::vector<std::vector<int>> confusion;       ///< [true][predicted]; the last column counts "unknown".
    std::vector<int> predictions;                  ///< Per clip: index into labels, or −1 for unknown.
    double clip_accuracy = 0;
    double unknown_rate = 0;
    std::vector<double> precision, recall;         ///< Per label (NaN-free: 0 when undefined).
};

/// Fills accuracy, unknown rate, precision and recall from predictions.
void summarise(ClipResults& results, const std::vector<LabelledClip>& clips);

/// The model's own method: each clip's string (runtime encoder) against the
/// representatives (runtime batch distance, kNN).
ClipResults evaluate_model(const ModelView& model, const std::vector<LabelledClip>& clips);

/// Baseline: 1-NN over every training clip's string (no representatives), same
/// model, same distance.
ClipResults evaluate_all_strings(const ModelView& model, const std::vector<LabelledClip>& train,
                                 const std::vector<LabelledClip>& clips);

/// Baseline: classic DTW 1-NN on normalised poses sampled at `rate_hz`
/// (Euclidean frame distance, whole-to-whole boundaries). Uses the model's
/// skeleton roles for normalisation.
ClipResults evaluate_pose_dtw(const ModelView& model, const std::vector<LabelledClip>& train,
                              const std::vector<LabelledClip>& clips, double rate_hz = 15.0);

/// Per-frame cost of the annotator over the clips' frames, in nanoseconds (sorted).
std::vector<double> annotator_frame_times(const ModelView& model, const std::vector<LabelledClip>& clips);

/// A JSON string literal (quotes and escapes included).
std::string json_string(const std::string& text);

/// The results as a JSON object: clip_accuracy, unknown_rate, labels,
/// confusion, per_class (precision, recall, support).
std::string to_json(const ClipResults& results, const std::vector<LabelledClip>& clips);

}  // namespace host
}  // namespace actionstring
