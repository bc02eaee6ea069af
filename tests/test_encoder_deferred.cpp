// Deferred characters (EncoderConfig::deferred, what AnnotatorConfig::spread_work
// uses): queued poses computed in stages over later calls give push_frame()'s
// characters and features, bit for bit, whatever the steps and the timing.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "actionstring/encoder.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"
#include "toy_options.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;

namespace {

struct Emitted {
    Character character = 0;
    std::uint32_t count = 0;
    std::vector<float> feature;
    std::vector<float> record;  // the pose it was projected from, then its facing turn
};

bool same(const Emitted& a, const Emitted& b) {
    return a.character == b.character && a.count == b.count && a.feature.size() == b.feature.size() &&
           std::memcmp(a.feature.data(), b.feature.data(), a.feature.size() * sizeof(float)) == 0 &&
           a.record.size() == b.record.size() &&
           std::memcmp(a.record.data(), b.record.data(), a.record.size() * sizeof(float)) == 0;
}

// The toy's actions joined, re-timed irregularly: jitter, repeated times,
// slow stretches (several ticks per frame, and ticks that take the previous
// frame twice), small steps back (rejected), NaN frames (rejected), a gap and
// a large step back (each restarts the stream).
struct Frames {
    std::vector<std::int64_t> times;
    std::vector<std::vector<float>> positions;
};

Frames irregular_frames(const host::ToyWorld& world, std::uint32_t seed) {
    host::ToyStreamOptions options;
    options.frame_rate_hz = 60.0;
    options.seed = seed;
    const auto stream = host::toy_stream(world, {0, 2, 1, 3, 0, 1}, options);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Frames out;
    double t = 5.0;
    for (std::size_t i = 0; i < stream.size(); ++i) {
        const double u = unit(rng);
        const bool slow = (i / 40) % 4 == 3;        // a quarter of the time at about 6 Hz
        if (i == stream.size() / 3) t += 1.5;       // a gap: restart
        else if (i == stream.size() / 2) t -= 0.5;  // far back: restart
        else if (u < 0.04) t -= 0.01;               // a small step back: rejected
        else if (u < 0.08) t += 0.0;                // the same instant
        else t += slow ? 0.12 + 0.1 * unit(rng) : (0.5 + unit(rng)) / 60.0;
        out.times.push_back(static_cast<std::int64_t>(t * 1e6));
        out.positions.push_back(stream[i].positions);
        if (unit(rng) < 0.02) out.positions.back()[3] = std::nanf("");  // rejected
    }
    return out;
}

void check_deferred_equals_eager(const ModelView& view, std::uint32_t seed) {
    host::Stateful<StringEncoder> eager, deferred;
    EncoderConfig later;
    later.deferred = true;
    REQUIRE(eager->init(view, EncoderConfig{}, nullptr, 0) != Status::ok);
    REQUIRE(eager.init(view, EncoderConfig{}) == Status::ok);
    REQUIRE(deferred.init(view, later) == Status::ok);
    CHECK(StringEncoder::required_bytes(view, later) > StringEncoder::required_bytes(view, EncoderConfig{}));
    const host::ToyWorld world = host::make_toy_world();
    const Frames frames = irregular_frames(world, seed);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::size_t> budget(0, 60);
    std::vector<Emitted> want, got;
    std::size_t restarts = 0, rejected = 0, two = 0, repeated = 0, partial = 0;
    const auto copy = [&](const float* feature) { return std::vector<float>(feature, feature + view.feature_dim); };
    const auto record = [&](const float* pose, const float* facing) {
        std::vector<float> r(pose, pose + view.pose_dim());
        r.insert(r.end(), facing, facing + 2);
        return r;
    };
    // One step of the oldest queued character: the work left falls; a character done is taken.
    const auto step = [&](std::size_t work) {
        const std::size_t before = deferred->deferred_work_left();
        const bool ready = deferred->advance_deferred(work);
        CHECK(deferred->deferred_work_left() < before);
        if (!ready) {
            CHECK(deferred->ready_character() == nullptr);
            ++partial;
            return;
        }
        const DeferredCharacter* c = deferred->ready_character();
        REQUIRE(c != nullptr);
        got.push_back(Emitted{c->character, c->count, copy(c->feature), record(c->pose, c->facing)});
        deferred->pop_character();
    };
    for (std::size_t i = 0; i < frames.times.size(); ++i) {
        const EncodedFrame a = eager->push_frame(frames.times[i], frames.positions[i].data());
        if (a.from_previous > 0)
            want.push_back(Emitted{a.previous, a.from_previous, copy(a.previous_feature),
                                   record(a.previous_pose, a.previous_facing)});
        if (a.from_current > 0)
            want.push_back(
                Emitted{a.current, a.from_current, copy(a.current_feature), record(a.current_pose, a.current_facing)});
        const EncodedFrame b = deferred->accept_frame(frames.times[i], frames.positions[i].data());
        REQUIRE(b.status == a.status);
        REQUIRE(b.from_previous == a.from_previous);
        REQUIRE(b.from_current == a.from_current);
        CHECK(b.previous_feature == nullptr);
        CHECK(b.current_feature == nullptr);
        CHECK(b.previous_pose == nullptr);
        CHECK(b.current_facing == nullptr);
        restarts += b.status == Status::stream_restarted;
        two += b.from_previous > 0 && b.from_current > 0;
        repeated += b.from_previous > 1 || b.from_current > 1;
        if (!b.accepted()) {
            ++rejected;
            CHECK(deferred->defer(b) == Status::invalid_argument);
        } else if (b.count() > 0) {
            // Room for one frame's poses: what is queued goes first.
            if (deferred->deferred_count() > 0) CHECK(deferred->defer(b) == Status::storage_too_small);
            while (deferred->deferred_count() > 0) step(budget(rng));
            REQUIRE(deferred->defer(b) == Status::ok);
            CHECK(deferred->deferred_count() == (b.from_previous > 0 ? 1u : 0u) + (b.from_current > 0 ? 1u : 0u));
        }
        for (std::size_t s = rng() % 3; s > 0 && deferred->deferred_count() > 0; --s) step(budget(rng));
    }
    while (deferred->deferred_count() > 0) step(budget(rng));
    CHECK(deferred->deferred_work_left() == 0);
    REQUIRE(got.size() == want.size());
    for (std::size_t k = 0; k < want.size(); ++k) CHECK(same(got[k], want[k]));
    CHECK(want.size() > 100);
    CHECK(restarts == 2);
    CHECK(rejected > 10);
    CHECK(two > 0);                    // frames whose ticks took both poses
    CHECK(repeated > 0);               // a pose taken by several ticks
    CHECK(2 * partial > want.size());  // many characters took several steps
    // An encoder that does not defer refuses, and reset() empties the queue.
    CHECK(eager->defer(EncodedFrame{}) == Status::invalid_argument);
    std::size_t finite = 0;
    while (std::isnan(frames.positions[finite][3])) ++finite;
    REQUIRE(deferred->defer(deferred->accept_frame(frames.times.back() + 5000000, frames.positions[finite].data())) ==
            Status::ok);
    CHECK(deferred->deferred_count() == 1);
    // push_frame() would overwrite the queued character's posterior: refused.
    CHECK(deferred->push_frame(frames.times.back() + 5100000, frames.positions[finite].data()).status ==
          Status::invalid_argument);
    CHECK(deferred->deferred_count() == 1);
    deferred->reset();
    CHECK(deferred->deferred_count() == 0);
    CHECK_FALSE(deferred->advance_deferred(10));
}

}  // namespace

TEST_CASE("deferred characters equal push_frame()'s, bit for bit, in any steps") {
    const host::ToyWorld world = host::make_toy_world();
    const auto clips = host::toy_clips(world, 2, 11);
    struct Variant {
        const char* name;
        int components, pca_dim;
        Covariance covariance;
        double velocity, acceleration;
    };
    const Variant variants[] = {
        {"GMM of 6, full, no projection", 6, 0, Covariance::full, 0.0, 0.0},
        {"GMM of 9, diagonal, no projection", 9, 0, Covariance::diagonal, 0.0, 0.0},
        {"projection, GMM of 13, full, velocity", 13, 5, Covariance::full, 1.0, 0.0},
        {"projection, no GMM, velocity and acceleration", 0, 7, Covariance::full, 1.0, 0.7},
        {"projection, GMM of 4, diagonal, acceleration", 4, 6, Covariance::diagonal, 0.0, 0.9},
    };
    std::uint32_t seed = 1;
    for (const Variant& v : variants) {
        INFO(std::string(v.name));
        host::TrainingOptions options = test::toy_options();
        options.components = v.components;
        options.pca_dim = v.pca_dim;
        options.covariance = v.covariance;
        options.velocity_weight = v.velocity;
        options.acceleration_weight = v.acceleration;
        if (v.velocity > 0.0) options.velocity_span_s = 0.3;
        options.keep_singletons = true;  // the encoder is under test, not the clustering
        const host::ModelData model = host::train_model(clips, options);
        const ModelView view = model.view();
        REQUIRE(view.has_gmm() == (v.components > 0));
        REQUIRE(view.has_projection() == (v.pca_dim > 0));
        for (int run = 0; run < 2; ++run) check_deferred_equals_eager(view, seed++);
    }
}
