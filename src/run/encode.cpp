// The runtime's encoder and sampler run over host clips.
#include "run/encode.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "actionstring/annotator.hpp"
#include "actionstring/encoder.hpp"
#include "actionstring/motion.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/sampler.hpp"
#include "run/state.hpp"
#include "common/time.hpp"
#include "run/skeleton.hpp"

namespace actionstring {
namespace host {
namespace {

// A clip is timed like a device's stream: a gap longer than the annotator's
// default restart gap starts the string afresh at the next frame instead of
// padding the gap with repeated characters, so no clip's string or pose list
// grows with its gaps.
constexpr AnnotatorConfig kDeviceTiming{};

}  // namespace

std::vector<Character> clip_string(const ModelView& model, const Clip& clip) {
    return encode_clip(model, clip, false).string;
}

EncodedClip encode_clip(const ModelView& model, const Clip& clip, bool with_features, bool with_records) {
    require_joint_count(model, clip.joint_count(), clip.source);
    Stateful<StringEncoder> encoder;
    const Status status = encoder.init(model, EncoderConfig{kDeviceTiming.max_gap_us, kDeviceTiming.max_backward_us});
    if (status == Status::invalid_argument)
        throw std::invalid_argument("the model's string period (" + std::to_string(model.string_period_us) +
                                    " us) is too short: a " + std::to_string(kDeviceTiming.max_gap_us) +
                                    " us gap would emit more than " + std::to_string(max_ticks_per_frame) +
                                    " characters in one frame");
    if (status != Status::ok)
        throw std::invalid_argument(std::string("model rejected by the encoder: ") + status_name(status));
    EncodedClip out;
    const std::size_t d = model.feature_dim;
    const std::size_t D = model.pose_dim();
    auto add_features = [&](const float* feature, const float* pose, const float* facing, std::uint32_t count) {
        for (std::uint32_t i = 0; i < count; ++i) {
            if (with_features) out.features.insert(out.features.end(), feature, feature + d);
            if (with_records) {
                out.records.insert(out.records.end(), pose, pose + D);
                out.records.insert(out.records.end(), facing, facing + 2);
            }
        }
    };
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const EncodedFrame e = encoder->push_frame(seconds_to_us(clip.times[f]), clip.frame(f));
        out.string.insert(out.string.end(), e.from_previous, e.previous);
        add_features(e.previous_feature, e.previous_pose, e.previous_facing, e.from_previous);
        out.string.insert(out.string.end(), e.from_current, e.current);
        add_features(e.current_feature, e.current_pose, e.current_facing, e.from_current);
    }
    return out;
}

std::size_t sample_poses(const ModelView& model, const Clip& clip, double rate_hz, std::vector<float>& poses) {
    require_joint_count(model, clip.joint_count(), clip.source);
    const auto period_us = static_cast<std::uint32_t>(std::lround(1e6 / rate_hz));
    if (!StringSampler::settings_ok(period_us, kDeviceTiming.max_gap_us, kDeviceTiming.max_backward_us))
        throw std::invalid_argument("cannot sample poses at " + std::to_string(rate_hz) + " Hz");
    StringSampler sampler;
    sampler.configure(period_us, kDeviceTiming.max_gap_us, kDeviceTiming.max_backward_us);
    const std::size_t D = model.input_dim();  // the pose, and with motion its velocity
    std::vector<float> previous(D), current(D), skeleton(3u * model.joint_count);
    Stateful<MotionRing> motion;
    if (motion.init(model) != Status::ok) throw std::invalid_argument("the model's motion settings are invalid");
    bool has_previous = false;
    std::size_t rejected = 0;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        if (normalize_pose(model, clip.frame(f), current.data(), skeleton.data()) != Status::ok) {
            ++rejected;
            continue;
        }
        const std::int64_t time_us = seconds_to_us(clip.times[f]);
        const SamplePlan plan = sampler.advance(time_us);
        if (plan.status == Status::time_went_backwards) continue;
        if (model.has_motion()) {  // as the encoder does, frame by frame
            if (plan.status == Status::stream_restarted) motion->reset();
            motion->update(model, time_us, current.data());
        }
        for (std::uint32_t i = 0; i < plan.from_previous && has_previous; ++i)
            poses.insert(poses.end(), previous.begin(), previous.end());
        for (std::uint32_t i = 0; i < plan.from_current; ++i) poses.insert(poses.end(), current.begin(), current.end());
        std::swap(previous, current);
        has_previous = true;
    }
    return rejected;
}

}  // namespace host
}  // namespace actionstring
