// The runtime's encoder and sampler run over host clips.
#include "run/encode.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "actionstring/capacity.hpp"
#include "actionstring/encoder.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/sampler.hpp"
#include "common/time.hpp"

namespace actionstring {
namespace host {
namespace {

// A clip is one stream: no gap in it restarts the encoder.
constexpr std::int64_t kNeverRestart = std::int64_t{1} << 62;

}  // namespace

std::vector<Character> clip_string(const ModelView& model, const Clip& clip) {
    auto encoder = std::make_unique<StringEncoder<HostCapacity>>();
    const Status status = encoder->init(model, kNeverRestart);
    if (status != Status::ok)
        throw std::invalid_argument(std::string("model rejected by the encoder: ") + status_name(status));
    std::vector<Character> string;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const EncodedFrame e = encoder->push_frame(seconds_to_us(clip.times[f]), clip.frame(f));
        string.insert(string.end(), e.from_previous, e.previous);
        string.insert(string.end(), e.from_current, e.current);
    }
    return string;
}

std::size_t sample_poses(const ModelView& model, const Clip& clip, double rate_hz, std::vector<float>& poses) {
    StringSampler sampler;
    sampler.configure(static_cast<std::uint32_t>(std::lround(1e6 / rate_hz)), kNeverRestart);
    const std::size_t D = model.pose_dim();
    std::vector<float> previous(D), current(D);
    bool has_previous = false;
    std::size_t rejected = 0;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        if (normalize_pose(model, clip.frame(f), current.data()) != Status::ok) {
            ++rejected;
            continue;
        }
        const SamplePlan plan = sampler.advance(seconds_to_us(clip.times[f]));
        if (plan.status == Status::time_went_backwards) continue;
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
