// actionstring host library — online labelling of unsegmented streams, judged
// frame by frame: concatenated clips or continuous recordings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/model.hpp"
#include "eval/significance.hpp"
#include "io/clip_list.hpp"
#include "io/recordings.hpp"
#include "run/stream_labels.hpp"

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
    double mean_delay_s = 0;  ///< From a true segment's start to its first correct label (found segments).
    /// How long after its frame each frame's label became final (the settled
    /// rule's: at most the settle delay, less with early settling), the median
    /// and the 95th percentile over the frames; 0 for rules whose labels come
    /// with their frame.
    double final_after_median_s = 0, final_after_p95_s = 0;
    int missed_segments = 0;  ///< True segments never labelled correctly.
    double label_changes_per_min = 0, true_changes_per_min = 0;
    double flicker_per_min = 0;  ///< Label changes per minute beyond the true ones (≥ 0).
    /// Frame-level F1 over the action classes, macro-averaged over the classes
    /// present in the truth ("no action" is not a class: an action called
    /// unknown is a miss, unknown called an action a false alarm).
    double frame_f1 = 0;
    /// "Unknown everywhere" on the same frames: its frame accuracy (the share of no-action frames).
    double unknown_everywhere_accuracy = 0;
    /// Frames by their true and predicted label, for per-class figures and
    /// for what an action's missed frames were taken for: row 0 is "no
    /// action" and row 1 + l label l (the truth); column 0 unknown and
    /// column 1 + l label l (the prediction); then one last row, the frames
    /// of labels the model does not know (truth −2, always wrong). (L + 2) ×
    /// (L + 1) counts, row by row, L = confusion_labels: one more than the
    /// highest label index of either side.
    std::size_t confusion_labels = 0;
    std::vector<std::size_t> frame_confusion;
    /// Frames of truth `row` and prediction `column` (−1: no action / unknown;
    /// row −2: a label the model does not know); 0 outside the table.
    std::size_t confused(int row, int column) const;

    /// From the action events (the settled rule only; zero for the others).
    bool has_events = false;
    std::size_t events = 0;          ///< Actions reported (started events).
    std::size_t matched_events = 0;  ///< Matched one-to-one to a true action of the same label that they overlap.
    double event_precision = 0, event_recall = 0, event_f1 = 0;
    /// The reported actions judged as segments: each matched one-to-one to a
    /// true action of its label with temporal IoU ≥ 0.5 (segment_f1's rule, on
    /// the events' own start and end instead of the settled labels' runs).
    std::size_t iou_matched_events = 0;
    double event_segment_f1 = 0;
    double detection_latency_s = 0;  ///< Mean, true start → the matched action's `started` report.
    double start_error_s = 0;        ///< Mean |reported start − true start| over matched actions.
    double end_error_s = 0;          ///< Mean |reported end − true end| over matched actions.
    /// Mean reported − true start (end) over matched actions: positive when the
    /// reports come late, the part of the error a constant offset would explain.
    double start_bias_s = 0, end_bias_s = 0;
    /// Unmatched actions per minute of no action; per minute of stream when
    /// the streams have no no-action frames (concatenated clips).
    double false_events_per_min = 0;
    bool false_events_per_stream_min = false;  ///< Which of the two minutes divides.

    /// One true run of the streams (an action, or a stretch of no action), in
    /// stream order, with what was scored on it: the units the intervals
    /// below resample. A predicted run or a reported action belongs to the
    /// true run its middle falls in.
    struct Unit {
        std::size_t frames = 0, right = 0;   ///< Its frames, and those labelled right.
        std::size_t true_segments = 0;       ///< 1 for an action (segment F1 counts it), 0 for no action.
        std::size_t matched = 0;             ///< 1 when a predicted run matched it (IoU ≥ 0.5).
        std::size_t predicted = 0;           ///< Predicted action runs centred in it.
        std::size_t true_actions = 0;        ///< 1 for an action the model knows (the events count it).
        std::size_t iou_matched_events = 0;  ///< 1 when a reported action matched it as a segment.
        std::size_t reported = 0;            ///< Reported actions centred in it.
    };
    std::vector<Unit> units;
    /// 95% intervals, resampling the units (bootstrap_ratio_interval(),
    /// significance.hpp; add_intervals()): frame accuracy, segment F1 and the
    /// events' segment F1.
    Interval frame_accuracy_interval, segment_f1_interval, event_segment_f1_interval;
    /// Frame accuracy minus "unknown everywhere"'s, 95%, resampling the same
    /// units: the two are scored on the same frames, so whether the labels
    /// beat saying nothing is read here, not from two intervals side by side.
    /// Where there is no "no action" it is the frame accuracy's.
    Interval gain_over_unknown_interval;
};

/// Fills the intervals of `results` from its units.
void add_intervals(OnlineResults& results);

/// One class's frames, read off OnlineResults::frame_confusion: "no action"
/// (label −1: its frames labelled unknown, and the unknown labels that were
/// no action) or an action.
struct FrameClassScore {
    int label = unknown_frame;
    std::size_t frames = 0;                    ///< True frames of the class.
    std::size_t right = 0;                     ///< Those labelled with it.
    std::size_t labelled = 0;                  ///< Frames labelled with it, rightly or not (of any truth, −2 too).
    double recall = 0, precision = 0, f1 = 0;  ///< 0 where undefined (nothing true, nothing labelled).
    /// What its wrongly labelled frames were most often taken for (−1
    /// unknown; ties to the lower index), and how many; most_taken_for_frames 0
    /// when none was wrong.
    int most_taken_for = unknown_frame;
    std::size_t most_taken_for_frames = 0;
};

/// "No action" first when the streams have any, then every label with true
/// frames, in label order.
std::vector<FrameClassScore> frame_class_scores(const OnlineResults& results);

/// A class's name in those tables: "no action" for −1, else labels[label]
/// (its number when out of range).
std::string frame_class_name(int label, const std::vector<std::string>& labels);

/// Scores a labelled timeline: per frame the true and predicted label (−1
/// unknown or "no action", −2 a label the model does not know), its time in
/// seconds, and where each independent stream starts (segments and label
/// changes never span two streams; the last start is the end). `emitted`, when
/// given, is when each frame's label was output (a settled label comes later
/// than its frame); label delay is measured to that time.
OnlineResults score_timeline(const std::vector<int>& truth, const std::vector<int>& predicted,
                             const std::vector<double>& times, const std::vector<std::size_t>& stream_starts,
                             const std::vector<double>* emitted = nullptr);

/// Scores action events against the timeline (fills the event fields of
/// `results`): per stream, each true action (a run of one label) is matched to
/// the first unmatched reported action of its label that overlaps it in time.
void score_events(OnlineResults& results, const std::vector<int>& truth, const std::vector<double>& times,
                  const std::vector<std::size_t>& stream_starts,
                  const std::vector<std::vector<ReportedEvent>>& stream_events);

/// One evaluated stream, for reports and pictures.
struct StreamTimeline {
    std::string name;
    std::vector<double> times_s;
    std::vector<int> truth;  ///< −1 "no action", −2 a label the model does not know; empty: not known.
    StreamLabels labels;
    /// The skeleton as streamed, for the viewer: frames × joints × xyz in
    /// metres, each joint's parent (−1 at a root; empty when the format has
    /// none) and the up axis.
    std::size_t joints = 0;
    std::vector<float> positions;
    std::vector<int> parents;
    int up_axis = 1;
};

/// Scores of the three rules on the same streams, and the streams themselves.
struct OnlineReport {
    /// Whole continuous recordings (frames outside every interval: no action),
    /// or clips concatenated per subject.
    bool recordings = false;
    OnlineResults settled, live, window;
    std::vector<StreamTimeline> streams;
    /// The settled labels scored on each stream alone, in the order of
    /// `streams` (a subject's clips joined, or one recording): which people or
    /// recordings the pooled figures come from. Their 95% intervals are not
    /// filled (add_intervals() resamples the pooled figures' units).
    std::vector<OnlineResults> per_stream;
};

/// Concatenates each subject's clips in a seeded shuffled order (the timeline
/// is known by construction), streams every frame with its timestamp through
/// the annotator as a device would, and scores every rule's labels. With
/// `paper_rule` false the window rule is not run and `window` is not measured
/// (label_stream()): the segmenter's figures are the same, at a fraction of the cost.
OnlineReport evaluate_online(const ModelView& model, const std::vector<LabelledClip>& clips, std::uint32_t seed,
                             const AnnotatorConfig& config, bool paper_rule = true);
/// The same with the model's own online settings (annotator_config()).
OnlineReport evaluate_online(const ModelView& model, const std::vector<LabelledClip>& clips, std::uint32_t seed);

/// Streams one recording whole, frame by frame, through the annotator and
/// keeps its skeleton (for the viewer). The truth comes from `intervals`
/// (frames outside every one: no action); with none given it is not known.
StreamTimeline stream_recording(const ModelView& model, const Clip& clip,
                                const std::vector<LabelledRecording::Interval>* intervals,
                                const AnnotatorConfig& config, bool paper_rule = true);

/// Streams every recording whole, frame by frame with its timestamps, through
/// the annotator and scores every rule against its timeline; frames outside
/// every interval count as "no action" (the right output there is unknown).
/// `paper_rule` as evaluate_online()'s.
OnlineReport evaluate_recordings(const ModelView& model, const std::vector<LabelledRecording>& recordings,
                                 const AnnotatorConfig& config, bool paper_rule = true);
/// The same with the model's own online settings (annotator_config()).
OnlineReport evaluate_recordings(const ModelView& model, const std::vector<LabelledRecording>& recordings);

}  // namespace host
}  // namespace actionstring
