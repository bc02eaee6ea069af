// What the model fuzz targets do with a model the fuzzer made and the runtime
// accepted: stream frames of a standing body through an annotator and check
// every label.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/model.hpp"
#include "run/state.hpp"

namespace actionstring {
namespace fuzz {

inline std::vector<float> frame_for(const ModelView& model, int step) {
    std::vector<float> frame(3u * model.joint_count);
    for (std::size_t j = 0; j < model.joint_count; ++j) {
        frame[3 * j + 0] = 0.05f * static_cast<float>(j % 7) + 0.01f * static_cast<float>(step % 13);
        frame[3 * j + 1] = 0.8f + 0.03f * static_cast<float>(j % 11);
        frame[3 * j + 2] = 0.02f * static_cast<float>(j % 5);
    }
    frame[3u * model.left_hip_joint] = 0.15f;
    frame[3u * model.right_hip_joint] = -0.15f;
    return frame;
}

/// An event's label is an action of the model, and its times are in order.
inline void check_events(const Annotator& annotator, const ModelView& view) {
    for (std::size_t i = 0; i < annotator.event_count(); ++i) {
        const ActionEvent& event = annotator.event(i);
        if (event.label >= view.label_count) std::abort();
        if (event.last_character < event.first_character || event.end_time_us < event.start_time_us) std::abort();
    }
}

/// Streams 40 frames through an annotator with both rules on a model that
/// passed validation, then flushes it; aborts (a finding) when init() refuses
/// it, or a label (live, settled, flushed or an event's) is out of range, a
/// label name empty or the confidence not finite. A model whose state would
/// exceed 64 MiB is valid but skipped.
inline void stream_and_check(const ModelView& view) {
    AnnotatorConfig config = annotator_config(view);
    config.window_rule = true;
    if (Annotator::required_bytes(view, config) > (std::size_t{64} << 20)) return;
    host::Stateful<Annotator> annotator;
    const Status status = annotator.init(view, config);
    if (status == Status::model_exceeds_capacity) return;
    if (status != Status::ok) std::abort();
    for (int step = 0; step < 40; ++step) {
        const std::vector<float> frame = frame_for(view, step);
        annotator->push_frame(static_cast<std::int64_t>(step) * 40000, frame.data());
        const LabelId label = annotator->label(), live = annotator->live_label();
        if (label != unknown_label && label >= view.label_count) std::abort();
        if (live != unknown_label && live >= view.label_count) std::abort();
        if (!std::isfinite(annotator->confidence())) std::abort();
        if (live != unknown_label && std::strlen(view.label_names[live]) == 0) std::abort();
        check_events(*annotator, view);
    }
    annotator->flush();
    check_events(*annotator, view);
    for (std::uint32_t i = 0; i < annotator->flushed_characters(); ++i) {
        const LabelId flushed = annotator->flushed_label(i);
        if (flushed != unknown_label && flushed >= view.label_count) std::abort();
    }
}

}  // namespace fuzz
}  // namespace actionstring
