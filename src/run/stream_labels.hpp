// actionstring host library — streaming frames through one annotator exactly
// as a device would, and the label timelines that come out.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/model.hpp"
#include "io/clip.hpp"

namespace actionstring {
namespace host {

/// A per-frame label in host timelines: a model label index (≥ 0) or one of these.
enum FrameLabel : int {
    /// Predicted: unknown. Truth: no action (the right prediction there is unknown).
    unknown_frame = -1,
    /// Truth only: a label the model does not know, so no prediction can match it.
    foreign_label = -2,
};

/// A model label as a FrameLabel index (unknown_label → unknown_frame).
constexpr int frame_label(LabelId label) noexcept {
    return label == unknown_label ? unknown_frame : static_cast<int>(label);
}

/// Per frame, what each online rule of the annotator said.
/// An action event and when the annotator reported it (the frame's time, in seconds).
struct ReportedEvent {
    ActionEvent event;
    double reported_s = 0;
};

struct StreamLabels {
    std::vector<int> window;            ///< The paper's rule: the latest window's label, output at the frame.
    std::vector<int> live;              ///< The segmenter's live label, output at the frame.
    std::vector<int> settled;           ///< The segmenter's final label of the frame's character.
    std::vector<float> margin;          ///< The live label's lead over every other label, at the frame (W units).
    std::vector<double> settled_at_s;   ///< When that final label was output.
    std::vector<ReportedEvent> events;  ///< Action events, the stream flushed at its end.
};

/// Why Annotator::init() refused a model and settings with
/// `status`, in words a user can act on (which field, which setting, which limit).
std::string annotator_refusal(const ModelView& model, const AnnotatorConfig& config, Status status);

/// Streams frames (times in seconds, joints × 3 floats each) through one
/// annotator exactly as a device would, and collects every rule's labels. The
/// unsettled tail at the end is reported from the best explanation then.
/// With `paper_rule` false the paper's window rule is not run (`window` stays
/// unknown): the segmenter's labels and events are the same, and most of the
/// work is saved when only they are wanted (self-tuning's online search).
StreamLabels label_stream(const ModelView& model, const AnnotatorConfig& config, const std::vector<double>& times_s,
                          const float* positions, std::size_t joints, bool paper_rule = true);

/// One stretch of time with a constant label from the annotator.
struct LabelSpan {
    double start_s = 0, end_s = 0;  ///< Times of the first frame and of the frame after the span (or the last frame).
    int label = unknown_frame;
    /// Share of the span's frames whose live label (decided without the settle
    /// delay) already said the final label: 1 = clear from the first frame.
    double agreement = 0;
    std::size_t frames = 0;
};

/// Streams a clip frame by frame through the annotator, flushes it at the
/// end, and returns every action event in order (started, ended).
std::vector<ActionEvent> stream_events(const ModelView& model, const Clip& clip, const AnnotatorConfig& config);

/// Streams a clip frame by frame through the annotator and returns the
/// timeline of settled labels: consecutive frames with the same label form one span.
std::vector<LabelSpan> annotate_clip(const ModelView& model, const Clip& clip, const AnnotatorConfig& config);
/// The same with the model's own online settings (annotator_config()).
std::vector<LabelSpan> annotate_clip(const ModelView& model, const Clip& clip);

}  // namespace host
}  // namespace actionstring
