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

/// Most characters one frame may emit: the restart gap over the string period
/// must not exceed it, so a frame's work stays bounded whatever its timestamp.
constexpr std::uint32_t max_ticks_per_frame = 4096;
/// Longest restart gap accepted (60 s): a longer silence is another stream.
constexpr std::int64_t max_gap_limit_us = 60000000;

/// Which frames the ticks that fell due at an incoming frame take their characters from.
struct SamplePlan {
    /// ok, stream_restarted (a gap longer than the maximum, or the clock went
    /// back further than the tolerance: tick 0 again at this frame), or
    /// time_went_backwards (a small step back: frame rejected, nothing changed).
    Status status = Status::ok;
    /// Earliest ticks, nearer to the previous accepted frame.
    std::uint32_t from_previous = 0;
    /// Later ticks, nearer to (or level with) this frame.
    std::uint32_t from_current = 0;
};

/// Time bookkeeping of the string sampler; owns no buffers.
class StringSampler {
public:
    /// Whether configure() accepts these settings: a period > 0; a restart gap
    /// of at least one period, at most max_gap_limit_us and at most
    /// max_ticks_per_frame periods; a backward tolerance in [0, max_gap_us].
    static constexpr bool settings_ok(std::uint32_t period_us, std::int64_t max_gap_us,
                                      std::int64_t max_backward_us) noexcept {
        return period_us > 0 && max_gap_us >= static_cast<std::int64_t>(period_us) &&
               max_gap_us <= max_gap_limit_us &&
               max_gap_us / period_us <= static_cast<std::int64_t>(max_ticks_per_frame) - 1 &&
               max_backward_us >= 0 && max_backward_us <= max_gap_us;
    }

    /// @param period_us       time between characters
    /// @param max_gap_us      a longer gap between accepted frames restarts the stream
    /// @param max_backward_us a frame at most this much earlier than the last
    ///                        one is rejected (jitter, reordering); further back,
    ///                        the clock was reset or wrapped, and the stream restarts
    /// The settings must pass settings_ok(); a frame then emits at most
    /// max_ticks_per_frame characters.
    void configure(std::uint32_t period_us, std::int64_t max_gap_us, std::int64_t max_backward_us) noexcept {
        period_us_ = period_us;
        max_gap_us_ = max_gap_us;
        max_backward_us_ = max_backward_us;
        reset();
    }

    void reset() noexcept {
        started_ = false;
        origin_us_ = 0;
        last_us_ = 0;
        next_tick_ = 0;
    }

    /// Ticks due when a frame at `time_us` is accepted, and commits to it.
    /// A frame at the same time as the previous one emits nothing. O(1).
    SamplePlan advance(std::int64_t time_us) noexcept {
        SamplePlan plan;
        if (started_ && time_us < last_us_) {
            if (offset(last_us_, time_us) <= static_cast<std::uint64_t>(max_backward_us_)) {
                plan.status = Status::time_went_backwards;
                return plan;
            }
            started_ = false;  // the clock was reset or wrapped: another stream
            plan.status = Status::stream_restarted;
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
        // Most frames owe no tick and most of the rest owe one: both are told
        // apart by a product, and the 64-bit divisions (a library call of
        // hundreds of instructions on a 32-bit core) run only after a gap.
        const std::uint64_t next_due = next_tick_ * period_us_;
        if (now >= next_due) {
            const std::uint64_t sum = last + now;  // < 2^64: both are offsets within one stream
            if (now - next_due < period_us_) {
                // One tick, k = next_tick_: it takes the previous frame when k·P − last < now − k·P.
                const bool previous = 2u * next_due < sum;
                plan.from_previous = previous ? 1u : 0u;
                plan.from_current = previous ? 0u : 1u;
                ++next_tick_;
            } else {
                // Ticks next_tick_ … last_due fell due (at most max_gap / period + 1 of
                // them). Tick k takes the previous frame when k·P − last < now − k·P,
                // that is when k < (last + now) / 2P: the first `from_previous` ticks.
                const std::uint64_t last_due = now / period_us_;
                const std::uint64_t two_periods = 2u * std::uint64_t{period_us_};
                const std::uint64_t first_current = (sum + two_periods - 1u) / two_periods;
                const std::uint64_t previous_end = first_current < next_tick_ ? next_tick_
                                                   : first_current > last_due + 1u ? last_due + 1u
                                                                                    : first_current;
                plan.from_previous = static_cast<std::uint32_t>(previous_end - next_tick_);
                plan.from_current = static_cast<std::uint32_t>(last_due + 1u - previous_end);
                next_tick_ = last_due + 1u;
            }
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
    std::int64_t max_backward_us_ = 0;
    bool started_ = false;
    std::int64_t origin_us_ = 0;
    std::int64_t last_us_ = 0;
    std::uint64_t next_tick_ = 0;
};

}  // namespace actionstring
