// actionstring host library — evaluation of clip recognition, with baselines.
#pragma once

#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/capacity.hpp"
#include "actionstring/model.hpp"
#include "actionstring_host/readers.hpp"
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
    /// Where much of a stream is "no action" (truth −1), frame accuracy rewards
    /// saying unknown everywhere; these two parts show the balance.
    std::size_t no_action_frames = 0;
    double action_frame_accuracy = 0;  ///< Over frames inside a labelled action.
    double no_action_accuracy = 0;     ///< Share of "no action" frames labelled unknown.
    double segment_precision = 0, segment_recall = 0, segment_f1 = 0;  ///< Temporal IoU ≥ 0.5, one-to-one.
    double mean_delay_s = 0;      ///< From a true segment's start to its first correct label (found segments).
    int missed_segments = 0;      ///< True segments never labelled correctly.
    double label_changes_per_min = 0, true_changes_per_min = 0;
    double flicker_per_min = 0;   ///< Label changes per minute beyond the true ones (≥ 0).
};

/// Scores a labelled timeline: per frame the true and predicted label (−1
/// unknown or "no action", −2 a label the model does not know), its time in
/// seconds, and where each independent stream starts (segments and label
/// changes never span two streams; the last start is the end). `emitted`, when
/// given, is when each frame's label was output (a settled label comes later
/// than its frame); label delay is measured to that time.
OnlineResults score_timeline(const std::vector<int>& truth, const std::vector<int>& predicted, const std::vector<double>& times,
                             const std::vector<std::size_t>& stream_starts, const std::vector<double>* emitted = nullptr);

/// Per frame, what each online rule of the annotator said (−1 unknown).
struct StreamLabels {
    std::vector<int> window;            ///< The paper's rule: the latest window's label, output at the frame.
    std::vector<int> live;              ///< The segmenter's live label, output at the frame.
    std::vector<int> settled;           ///< The segmenter's final label of the frame's character.
    std::vector<double> settled_at_s;   ///< When that final label was output.
};

/// Streams frames (times in seconds, joints × 3 floats each) through one
/// annotator exactly as a device would, and collects every rule's labels. The
/// unsettled tail at the end is reported from the best explanation then.
StreamLabels label_stream(const ModelView& model, const AnnotatorConfig& config, const std::vector<double>& times_s,
                          const float* positions, std::size_t joints);

/// One evaluated stream, for reports and pictures.
struct StreamTimeline {
    std::string name;
    std::vector<double> times_s;
    std::vector<int> truth;  ///< −1 "no action", −2 a label the model does not know.
    StreamLabels labels;
};

/// Scores of the three rules on the same streams, and the streams themselves.
struct OnlineReport {
    OnlineResults settled, live, window;
    std::vector<StreamTimeline> streams;
};

/// Concatenates each subject's clips in a seeded shuffled order (the timeline
/// is known by construction), streams every frame with its timestamp through
/// the annotator as a device would, and scores every rule's labels.
OnlineReport evaluate_online(const ModelView& model, const std::vector<LabelledClip>& clips, std::uint32_t seed,
                             const AnnotatorConfig& config = {});

/// A continuous recording with its labelled intervals (seconds on the clip's
/// time axis); every frame outside them is "no action".
struct LabelledRecording {
    std::string subject;
    Clip clip;
    struct Interval {
        std::string label;
        double start_s = 0, end_s = 0;
    };
    std::vector<Interval> intervals;
};

/// Groups a clip list's interval entries by file (first appearance order) and
/// reads each file once, whole. Entries without an interval are refused.
std::vector<LabelledRecording> read_recordings(const std::vector<ClipListEntry>& entries, const ReadOptions& read = {});

/// Streams every recording whole, frame by frame with its timestamps, through
/// the annotator and scores every rule against its timeline; frames outside
/// every interval count as "no action" (the right output there is unknown).
OnlineReport evaluate_recordings(const ModelView& model, const std::vector<LabelledRecording>& recordings,
                                 const AnnotatorConfig& config = {});

}  // namespace host
}  // namespace actionstring

namespace actionstring {
namespace host {

/// One stretch of time with a constant label from the annotator.
struct LabelSpan {
    double start_s = 0, end_s = 0;  ///< Times of the first frame and of the frame after the span (or the last frame).
    int label = -1;                 ///< −1 for unknown.
    /// Share of the span's frames whose live label (decided without the settle
    /// delay) already said the final label: 1 = clear from the first frame.
    double agreement = 0;
    std::size_t frames = 0;
};

/// Streams a clip frame by frame through the annotator and returns the
/// timeline of settled labels: consecutive frames with the same label form one span.
std::vector<LabelSpan> annotate_clip(const ModelView& model, const Clip& clip, const AnnotatorConfig& config = {});

}  // namespace host
}  // namespace actionstring
