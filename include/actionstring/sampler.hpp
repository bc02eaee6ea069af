// actionstring — stage 5: turns timestamped frames into string ticks (design.md §1.5).
//
// Characters are emitted at a fixed rate in *time*: tick k falls at
// origin + k × period, where the origin is the first accepted frame. Each tick
// takes the character of the frame nearest to it in time, so dropped,
// irregular or repeated frames leave the string rate unchanged.
#pragma once

#include <cstdint>

#include "actionstring/status.hpp"

namespace actionstring {

/// Which frames the ticks that fell due at an incoming frame take their characters from.
struct SamplePlan {
    /// ok, stream_restarted (a gap longer than the maximum: tick 0 again at
    /// this frame), or time_went_backwards (frame rejected, nothing changed).
    Status status = Status::ok;
    /// Earliest ticks, nearer to the previous accepted frame.
    std::uint32_t from_previous = 0;
    /// Later ticks, nearer to (or level with) this frame.
    std::uint32_t from_current = 0;
};

/// Time bookkeeping of the string sampler; owns no buffers.
class StringSampler {
public:
    /// @param period_us  time between characters, > 0
    /// @param max_gap_us a longer gap between accepted frames restarts the stream
    ///                   (bounds the characters one frame can emit to max_gap / period + 1)
    void configure(std::uint32_t period_us, std::int64_t max_gap_us) noexcept {
        period_us_ = period_us;
        max_gap_us_ = max_gap_us;
        reset();
    }

    void reset() noexcept {
        started_ = false;
        origin_us_ = 0;
        last_us_ = 0;
        next_tick_ = 0;
    }

    /// Ticks due when a frame at `time_us` is accepted, and commits to it.
    /// A frame at the same time as the previous one emits nothing.
    SamplePlan advance(std::int64_t time_us) noexcept {
        SamplePlan plan;
        if (started_ && time_us < last_us_) {
            plan.status = Status::time_went_backwards;
            return plan;
        }
        if (started_ && offset(time_us, last_us_) > static_cast<std::uint64_t>(max_gap_us_)) {
            started_ = false;
            plan.status = Status::stream_restarted;
        }
        if (!started_) {
            started_ = true;
            origin_us_ = last_us_ = time_us;
            next_tick_ = 1;
            plan.from_current = 1;  // tick 0 sits on this frame
            return plan;
        }
        // Offsets from the origin in unsigned arithmetic: no overflow for any int64 times.
        const std::uint64_t last = offset(last_us_, origin_us_);
        const std::uint64_t now = offset(time_us, origin_us_);
        const std::uint64_t last_due = now / period_us_;
        for (; next_tick_ <= last_due; ++next_tick_) {
            const std::uint64_t tick = next_tick_ * period_us_;
            if (tick - last < now - tick) ++plan.from_previous;
            else ++plan.from_current;
        }
        last_us_ = time_us;
        return plan;
    }

    bool started() const noexcept { return started_; }
    /// Time of tick k of the current stream.
    std::int64_t tick_time_us(std::uint64_t tick) const noexcept {
        return static_cast<std::int64_t>(static_cast<std::uint64_t>(origin_us_) + tick * period_us_);
    }
    std::uint32_t period_us() const noexcept { return period_us_; }

private:
    static std::uint64_t offset(std::int64_t later, std::int64_t earlier) noexcept {
        return static_cast<std::uint64_t>(later) - static_cast<std::uint64_t>(earlier);
    }

    std::uint32_t period_us_ = 1;
    std::int64_t max_gap_us_ = 0;
    bool started_ = false;
    std::int64_t origin_us_ = 0;
    std::int64_t last_us_ = 0;
    std::uint64_t next_tick_ = 0;
};

}  // namespace actionstring
