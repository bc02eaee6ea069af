// actionstring host library — online labelling of unsegmented streams, judged
// frame by frame: concatenated clips or continuous recordings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/model.hpp"
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
    int missed_segments = 0;  ///< True segments never labelled correctly.
    double label_changes_per_min = 0, true_changes_per_min = 0;
    double flicker_per_min = 0;  ///< Label changes per minute beyond the true ones (≥ 0).
};

/// Scores a labelled timeline: per frame the true and predicted label (−1
/// unknown or "no action", −2 a label the model does not know), its time in
/// seconds, and where each independent stream starts (segments and label
/// changes never span two streams; the last start is the end). `emitted`, when
/// given, is when each frame's label was output (a settled label comes later
/// than its frame); label delay is measured to that time.
OnlineResults score_timeline(const std::vector<int>& truth, const std::vector<int>& predicted,
                             const std::vector<double>& times, const std::vector<std::size_t>& stream_starts,
                             const std::vector<double>* emitted = nullptr);

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
                             const AnnotatorConfig& config);
/// The same with the model's own online settings (annotator_config()).
OnlineReport evaluate_online(const ModelView& model, const std::vector<LabelledClip>& clips, std::uint32_t seed);

/// Streams every recording whole, frame by frame with its timestamps, through
/// the annotator and scores every rule against its timeline; frames outside
/// every interval count as "no action" (the right output there is unknown).
OnlineReport evaluate_recordings(const ModelView& model, const std::vector<LabelledRecording>& recordings,
                                 const AnnotatorConfig& config);
/// The same with the model's own online settings (annotator_config()).
OnlineReport evaluate_recordings(const ModelView& model, const std::vector<LabelledRecording>& recordings);

}  // namespace host
}  // namespace actionstring
