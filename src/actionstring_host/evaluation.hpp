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

namespace actionstring {
namespace host {

/// Online labelling of unsegmented streams, judged frame by frame.
struct OnlineResults {
    std::size_t frames = 0;
    double frame_accuracy = 0;
    double segment_precision = 0, segment_recall = 0, segment_f1 = 0;  ///< Temporal IoU ≥ 0.5, one-to-one.
    double mean_delay_s = 0;      ///< From a true segment's start to its first correct label (found segments).
    int missed_segments = 0;      ///< True segments never labelled correctly.
    double label_changes_per_min = 0, true_changes_per_min = 0;
    double flicker_per_min = 0;   ///< Label changes per minute beyond the true ones (≥ 0).
};

/// Scores a labelled timeline: per frame the true and predicted label (−1
/// unknown), its time in seconds, and where each independent stream starts
/// (segments and label changes never span two streams; the last start is the end).
OnlineResults score_timeline(const std::vector<int>& truth, const std::vector<int>& predicted, const std::vector<double>& times,
                             const std::vector<std::size_t>& stream_starts);

/// Concatenates each subject's clips in a seeded shuffled order (the timeline
/// is known by construction), streams every frame with its timestamp through
/// the annotator as a device would, and scores the label after each frame.
OnlineResults evaluate_online(const ModelView& model, const std::vector<LabelledClip>& clips, std::uint32_t seed);

}  // namespace host
}  // namespace actionstring

namespace actionstring {
namespace host {

/// One stretch of time with a constant label from the annotator.
struct LabelSpan {
    double start_s = 0, end_s = 0;  ///< Times of the first frame and of the frame after the span (or the last frame).
    int label = -1;                 ///< −1 for unknown.
    double mean_confidence = 0;     ///< Over the span's frames.
    std::size_t frames = 0;
};

/// Streams a clip frame by frame through the annotator and returns the label
/// timeline: consecutive frames with the same label form one span.
std::vector<LabelSpan> annotate_clip(const ModelView& model, const Clip& clip);

}  // namespace host
}  // namespace actionstring
