// String sampling by time: rate independent of frame rate, jitter, drops, repeats.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "actionstring/encoder.hpp"
#include "actionstring/sampler.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"

using namespace actionstring;

TEST_CASE("one tick per period, on the frame nearest in time") {
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        const std::uint32_t period = 20000 + static_cast<std::uint32_t>(unit(rng) * 200000);
        StringSampler sampler;
        sampler.configure(period, 2000000, 0);
        // Irregular frame times: random steps between 0 and 150 ms, some repeated.
        std::vector<std::int64_t> times{static_cast<std::int64_t>(unit(rng) * 1e9) - 500000000};
        for (int f = 0; f < 300; ++f)
            times.push_back(times.back() + (unit(rng) < 0.1 ? 0 : static_cast<std::int64_t>(unit(rng) * 150000)));
        // Expected: tick k at t0 + k·period goes to the nearest frame, the later one on a tie.
        std::vector<std::size_t> expected_owner;
        for (std::int64_t k = 0; times[0] + k * period <= times.back(); ++k) {
            const std::int64_t tick = times[0] + k * period;
            std::size_t best = 0;
            for (std::size_t f = 0; f < times.size(); ++f)
                if (std::llabs(times[f] - tick) <= std::llabs(times[best] - tick)) best = f;
            expected_owner.push_back(best);
        }
        std::vector<std::size_t> owner;
        std::size_t previous = 0;
        for (std::size_t f = 0; f < times.size(); ++f) {
            const SamplePlan plan = sampler.advance(times[f]);
            REQUIRE(plan.status == Status::ok);
            owner.insert(owner.end(), plan.from_previous, previous);
            owner.insert(owner.end(), plan.from_current, f);
            previous = f;
        }
        // A repeated timestamp is one instant: compare owners by their times.
        REQUIRE(owner.size() == expected_owner.size());
        for (std::size_t k = 0; k < owner.size(); ++k) CHECK(times[owner[k]] == times[expected_owner[k]]);
    }
}

TEST_CASE("a small step back is rejected and a long gap restarts the stream") {
    StringSampler sampler;
    sampler.configure(100000, 1000000, 200000);
    CHECK(sampler.advance(5000000).from_current == 1);
    SamplePlan plan = sampler.advance(5250000);
    CHECK(plan.from_previous + plan.from_current == 2);
    plan = sampler.advance(5100000);
    CHECK(plan.status == Status::time_went_backwards);
    CHECK(plan.from_previous + plan.from_current == 0);
    plan = sampler.advance(5300000);  // ticks at 5.3 s: only one since 5.25 s
    CHECK(plan.status == Status::ok);
    CHECK(plan.from_previous + plan.from_current == 1);
    plan = sampler.advance(6300001);  // 1.000001 s later
    CHECK(plan.status == Status::stream_restarted);
    CHECK(plan.from_current == 1);
    CHECK(sampler.tick_time_us(0) == 6300001);
    CHECK(sampler.tick_time_us(3) == 6600001);
}

TEST_CASE("a clock that jumps back beyond the tolerance restarts the stream at once") {
    StringSampler sampler;
    sampler.configure(100000, 1000000, 100000);
    CHECK(sampler.advance(5000000).from_current == 1);
    CHECK(sampler.advance(4950000).status == Status::time_went_backwards);  // 50 ms back: jitter
    const SamplePlan plan = sampler.advance(4800000);                      // 200 ms back: a reset clock
    CHECK(plan.status == Status::stream_restarted);
    CHECK(plan.from_current == 1);
    CHECK(sampler.tick_time_us(0) == 4800000);
    const SamplePlan next = sampler.advance(4900000);  // one period on: the stream goes on from there
    CHECK(next.status == Status::ok);
    CHECK(next.from_previous + next.from_current == 1);
}

TEST_CASE("a wrapping 32-bit microsecond clock loses one frame per wrap, not the rest of the stream") {
    // 3 hours at 30 Hz through a timer that wraps every 2^32 us (71.6 minutes).
    StringSampler sampler;
    sampler.configure(83333, 1000000, 100000);
    std::uint64_t rejected = 0, restarted = 0, ticks = 0;
    const std::uint64_t frames = 3ull * 3600 * 30;
    for (std::uint64_t f = 0; f < frames; ++f) {
        const std::uint64_t true_us = f * 1000000 / 30;
        const auto timer = static_cast<std::uint32_t>(true_us);  // what the device reads
        const SamplePlan plan = sampler.advance(static_cast<std::int64_t>(timer));
        rejected += plan.status == Status::time_went_backwards;
        restarted += plan.status == Status::stream_restarted;
        ticks += plan.from_previous + plan.from_current;
    }
    CHECK(rejected == 0);
    CHECK(restarted == 2);  // one per wrap
    // 12 characters a second throughout, give or take one tick per restart.
    CHECK(static_cast<double>(ticks) == doctest::Approx(3.0 * 3600 * 12).epsilon(0.001));
}

TEST_CASE("the O(1) tick split equals a tick-by-tick reference on random timestamps") {
    // Odd trials step by at most two periods, so most frames owe no tick or
    // one (the sampler's path without divisions); even trials by up to the
    // whole gap, so most owe several.
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        const auto period = static_cast<std::uint32_t>(std::uniform_int_distribution<int>(1000, 200000)(rng));
        const std::int64_t max_gap = static_cast<std::int64_t>(period) * 40;
        StringSampler sampler;
        sampler.configure(period, max_gap, 0);
        std::int64_t t = std::uniform_int_distribution<std::int64_t>(-1000000000, 1000000000)(rng);
        // Reference: the last accepted time, the origin and the next tick.
        std::int64_t origin = t, last = t;
        std::uint64_t next = 1;
        REQUIRE(sampler.advance(t).from_current == 1);
        for (int f = 0; f < 300; ++f) {
            const std::int64_t step_limit = trial % 2 == 1 ? 2 * static_cast<std::int64_t>(period) : max_gap;
            t += std::uniform_int_distribution<std::int64_t>(0, step_limit)(rng);
            std::uint32_t from_previous = 0, from_current = 0;
            const auto now = static_cast<std::uint64_t>(t - origin), before = static_cast<std::uint64_t>(last - origin);
            for (; next <= now / period; ++next) {
                const std::uint64_t tick = next * period;
                if (tick - before < now - tick) ++from_previous;
                else ++from_current;
            }
            last = t;
            const SamplePlan plan = sampler.advance(t);
            REQUIRE(plan.status == Status::ok);
            REQUIRE(plan.from_previous == from_previous);
            REQUIRE(plan.from_current == from_current);
        }
    }
}

TEST_CASE("settings that would let one frame emit unbounded characters are refused") {
    CHECK(StringSampler::settings_ok(83333, 1000000, 100000));
    CHECK_FALSE(StringSampler::settings_ok(1, 1000000, 0));         // 10^6 characters in one gap
    CHECK_FALSE(StringSampler::settings_ok(83333, 61000000, 0));    // a gap over 60 s
    CHECK_FALSE(StringSampler::settings_ok(83333, 50000, 0));       // a gap shorter than a period
    CHECK_FALSE(StringSampler::settings_ok(83333, 1000000, 2000000));  // tolerance beyond the gap
    CHECK_FALSE(StringSampler::settings_ok(0, 1000000, 0));
}

TEST_CASE("extreme timestamps do not overflow") {
    StringSampler sampler;
    sampler.configure(100000, 1000000, 0);
    const std::int64_t late = std::numeric_limits<std::int64_t>::max() - 500000;
    CHECK(sampler.advance(late).from_current == 1);
    const SamplePlan plan = sampler.advance(late + 450000);
    CHECK(plan.status == Status::ok);
    CHECK(plan.from_previous + plan.from_current == 4);
    StringSampler early;
    early.configure(100000, 1000000, 0);
    CHECK(early.advance(std::numeric_limits<std::int64_t>::min()).from_current == 1);
    const SamplePlan later = early.advance(std::numeric_limits<std::int64_t>::min() + 200000);
    CHECK(later.from_previous + later.from_current == 2);
}

TEST_CASE("the same performance gives the same string at any frame rate") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    auto encode = [&](double rate, double jitter, double drop) {
        host::ToyStreamOptions options;
        options.frame_rate_hz = rate;
        options.frame_time_jitter = jitter;
        options.drop_probability = drop;
        options.position_noise_m = 0.0;
        options.seed = 9;  // same actions, places and facings for every rate
        host::Stateful<StringEncoder> encoder;
        REQUIRE(encoder.init(view, EncoderConfig{1000000, 0}) == Status::ok);
        std::vector<Character> string;
        std::int64_t first = -1, last = 0;
        for (const auto& frame : host::toy_stream(world, {0, 1, 2, 3, 1}, options)) {
            const EncodedFrame e = encoder->push_frame(frame.time_us, frame.positions.data());
            REQUIRE(e.accepted());
            if (first < 0) first = frame.time_us;
            last = frame.time_us;
            string.insert(string.end(), e.from_previous, e.previous);
            string.insert(string.end(), e.from_current, e.current);
        }
        CHECK(string.size() == static_cast<std::size_t>((last - first) / view.string_period_us + 1));
        return string;
    };
    const std::vector<Character> reference = encode(120.0, 0.0, 0.0);
    for (const auto& setting : {std::tuple{30.0, 0.0, 0.0}, std::tuple{60.0, 0.3, 0.0}, std::tuple{30.0, 0.4, 0.2},
                                std::tuple{15.0, 0.0, 0.0}}) {
        const double rate = std::get<0>(setting), jitter = std::get<1>(setting), drop = std::get<2>(setting);
        CAPTURE(rate);
        CAPTURE(drop);
        const std::vector<Character> other = encode(rate, jitter, drop);
        // Lengths differ only by where the last frame falls; characters only near pose changes.
        CHECK(std::abs(static_cast<long>(other.size()) - static_cast<long>(reference.size())) <= 1);
        std::size_t differing = 0;
        for (std::size_t i = 0; i < std::min(other.size(), reference.size()); ++i)
            differing += other[i] != reference[i];
        CHECK(static_cast<double>(differing) <= 0.08 * static_cast<double>(reference.size()));
    }
}
