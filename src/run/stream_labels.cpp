// Frames streamed through one annotator as a device would.
#include "run/stream_labels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <memory>
#include <stdexcept>

#include "common/time.hpp"
#include "run/skeleton.hpp"
#include "run/state.hpp"

namespace actionstring {
namespace host {
namespace {

// A character whose final label has not come yet.
constexpr int not_settled = -3;

}  // namespace

std::string annotator_refusal(const ModelView& model, const AnnotatorConfig& config, Status status) {
    const char* problem = "";
    if (validate_model(model, &problem) != Status::ok) return std::string("invalid model: ") + problem;
    const SegmenterConfig& s = config.segmenter;
    const double period_s = us_to_seconds(model.string_period_us);
    const double settle_chars = std::round(us_to_seconds(s.settle_delay_us) / period_s);
    if (s.settle_delay_us < 0 || s.settle_delay_us > max_settle_delay_us)
        return "a settle delay of " + std::to_string(us_to_seconds(s.settle_delay_us)) + " s (" +
               std::to_string(static_cast<long long>(settle_chars)) + " characters at the model's " +
               std::to_string(1.0 / period_s) + " Hz string rate) is outside 0 to " +
               std::to_string(us_to_seconds(max_settle_delay_us)) + " s";
    if (!StringSampler::settings_ok(model.string_period_us, config.max_gap_us, config.max_backward_us))
        return "a restart gap of " + std::to_string(config.max_gap_us) + " us and a backward tolerance of " +
               std::to_string(config.max_backward_us) + " us do not suit the model's " +
               std::to_string(model.string_period_us) + " us string period (at most 60 s and " +
               std::to_string(max_ticks_per_frame) + " periods; the tolerance at most the gap)";
    if (!(config.up[0] == 0.0f && config.up[1] == 0.0f && config.up[2] == 0.0f)) {
        float rotation[9];
        if (up_rotation(config.up, model.up_axis, rotation) != Status::ok) {
            char text[96];
            std::snprintf(text, sizeof text, "(%g, %g, %g)", static_cast<double>(config.up[0]),
                          static_cast<double>(config.up[1]), static_cast<double>(config.up[2]));
            return std::string("an up direction of ") + text +
                   " is not a direction: three finite numbers, longer than 1e-6 (0, 0, 0 for none)";
        }
    }
    if (status == Status::model_exceeds_capacity)
        return "a representative of the model (" + std::to_string(model.total_representative_chars()) +
               " characters in all) with the window is longer than 16-bit path lengths hold";
    if (status == Status::storage_too_small)
        return "the annotator's state for this model and settings (" +
               std::to_string(Annotator::required_bytes(model, config)) + " bytes) cannot be allocated";
    return std::string("the annotator refused the model or its settings: ") + status_name(status) +
           " (penalties and costs must be finite and at least 0)";
}

StreamLabels label_stream(const ModelView& model, const AnnotatorConfig& config, const std::vector<double>& times_s,
                          const float* positions, std::size_t joints, bool paper_rule) {
    require_joint_count(model, joints, "the stream");
    // Every rule, the paper's window rule included unless not wanted.
    AnnotatorConfig every_rule = config;
    every_rule.window_rule = paper_rule;
    Stateful<Annotator> annotator;
    const Status status = annotator.init(model, every_rule);
    if (status != Status::ok) throw std::invalid_argument(annotator_refusal(model, config, status));
    const std::size_t frames = times_s.size();
    StreamLabels out;
    out.window.assign(frames, unknown_frame);
    out.live.assign(frames, unknown_frame);
    out.settled.assign(frames, unknown_frame);
    out.margin.assign(frames, 0.0f);
    out.settled_at_s.assign(frames, 0.0);
    // Characters of every stream epoch (a restart begins a new one), with their final label, when it
    // came and the time it applies from (the runtime's label time).
    std::vector<int> char_label;
    std::vector<double> char_emitted;
    std::vector<std::int64_t> char_time_us;
    std::vector<std::size_t> frame_epoch(frames, 0);
    std::size_t epoch = 0;  // index in char_label of the current epoch's character 0
    // The labels an ended stream's last characters took when it ended (a restart, or the
    // flush at the end), emitted now; any the annotator did not give stay unknown.
    const auto take_flushed = [&](double now) {
        for (std::size_t i = 0; i < annotator->flushed_characters(); ++i) {
            const std::size_t c = epoch + static_cast<std::size_t>(annotator->flushed_character(i));
            if (c < char_label.size() && char_label[c] == not_settled)
                char_label[c] = frame_label(annotator->flushed_label(i)), char_emitted[c] = now;
        }
        for (std::size_t c = epoch; c < char_label.size(); ++c)
            if (char_label[c] == not_settled) char_label[c] = unknown_frame, char_emitted[c] = now;
    };
    for (std::size_t f = 0; f < frames; ++f) {
        const double now = times_s[f];
        const FrameResult r = annotator->push_frame(seconds_to_us(now), positions + f * joints * 3);
        if (r.status == Status::stream_restarted) {
            take_flushed(now);
            epoch = char_label.size();
        }
        while (char_label.size() < epoch + annotator->characters()) {
            char_time_us.push_back(annotator->label_time_us(char_label.size() - epoch));
            char_label.push_back(not_settled);
            char_emitted.push_back(now);
        }
        if (r.characters_settled > 0) {
            const std::uint64_t last = annotator->settled_character();
            for (std::uint64_t k = 0; k < r.characters_settled; ++k) {
                const std::uint64_t c = last - (r.characters_settled - 1 - k);
                char_label[epoch + c] = frame_label(annotator->settled_label(c));
                char_emitted[epoch + c] = now;
            }
        }
        for (std::size_t i = 0; i < r.events; ++i) out.events.push_back({annotator->event(i), now});
        out.window[f] = frame_label(annotator->label());
        out.live[f] = frame_label(annotator->live_label());
        out.margin[f] = annotator->live_margin();
        frame_epoch[f] = epoch;
    }
    if (frames > 0) {
        // At the end of the stream, the unsettled tail gets what the best explanation says of it then
        // (a character whose work is still spread over frames, with spread_work, finished first).
        const std::uint32_t events = annotator->flush();
        take_flushed(times_s.back());
        for (std::size_t i = 0; i < events; ++i) out.events.push_back({annotator->event(i), times_s.back()});
    }
    // Each frame takes the label of its epoch's last character whose label time is at most the
    // frame's (with a label lead, a character that came after it); unknown before the first.
    std::vector<std::size_t> epoch_end(frames, char_label.size());  // one past each frame's epoch's last character
    for (std::size_t f = frames; f-- > 1;)
        epoch_end[f - 1] = frame_epoch[f] != frame_epoch[f - 1] ? frame_epoch[f] : epoch_end[f];
    std::size_t next = 0;  // the first character whose label time is after the frame's, or its epoch's end
    for (std::size_t f = 0; f < frames; ++f) {
        const std::size_t first = frame_epoch[f], end = epoch_end[f];
        const std::int64_t now_us = seconds_to_us(times_s[f]);
        if (next < first) next = first;
        while (next < end && char_time_us[next] <= now_us) ++next;
        if (next == first) {
            out.settled_at_s[f] = times_s[f];
            continue;
        }
        const std::size_t c = next - 1;
        out.settled[f] = char_label[c] == not_settled ? unknown_frame : char_label[c];
        out.settled_at_s[f] = std::max(char_emitted[c], times_s[f]);
    }
    return out;
}

std::vector<ActionEvent> stream_events(const ModelView& model, const Clip& clip, const AnnotatorConfig& config) {
    require_joint_count(model, clip.joint_count(), clip.source);
    Stateful<Annotator> annotator;
    const Status status = annotator.init(model, config);
    if (status != Status::ok) throw std::invalid_argument(annotator_refusal(model, config, status));
    std::vector<ActionEvent> events;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const FrameResult r = annotator->push_frame(seconds_to_us(clip.times[f]), clip.frame(f));
        for (std::size_t i = 0; i < r.events; ++i) events.push_back(annotator->event(i));
    }
    const std::uint32_t flushed = annotator->flush();
    for (std::size_t i = 0; i < flushed; ++i) events.push_back(annotator->event(i));
    return events;
}

std::vector<LabelSpan> annotate_clip(const ModelView& model, const Clip& clip, const AnnotatorConfig& config) {
    const StreamLabels labels = label_stream(model, config, clip.times, clip.positions.data(), clip.joint_count());
    std::vector<LabelSpan> spans;
    std::size_t agreeing = 0;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const int label = labels.settled[f];
        if (spans.empty() || spans.back().label != label) {
            if (!spans.empty()) spans.back().end_s = clip.times[f];
            spans.push_back({clip.times[f], clip.times[f], label, 0.0, 0});
            agreeing = 0;
        }
        LabelSpan& span = spans.back();
        agreeing += labels.live[f] == label;
        ++span.frames;
        span.agreement = static_cast<double>(agreeing) / static_cast<double>(span.frames);
        span.end_s = clip.times[f];
    }
    return spans;
}

std::vector<LabelSpan> annotate_clip(const ModelView& model, const Clip& clip) {
    return annotate_clip(model, clip, annotator_config(model));
}

}  // namespace host
}  // namespace actionstring
