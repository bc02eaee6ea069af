// The velocity and acceleration beside the pose (motion.hpp): measured over
// time, so frame rate, jitter and dropped frames leave them unchanged; zero
// until the ring holds a pose old enough; forgotten at a restart; bounded.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "actionstring/motion.hpp"
#include "actionstring/encoder.hpp"
#include "model/artifact.hpp"
#include "run/encode.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;

namespace {

// A view with one pose joint (D = 3) and motion: all the ring reads.
ModelView motion_view(float weight, std::uint32_t span_us, float acceleration = 0.0f) {
    ModelView m;
    m.pose_joint_count = 1;
    m.velocity_weight = weight;
    m.velocity_span_us = span_us;
    m.acceleration_weight = acceleration;
    return m;
}

// Streams x(t) = (0.8 t, 0.3 t², 1) at the given times; returns each frame's
// motion (what follows the pose: velocity and acceleration, as the view has).
std::vector<std::vector<float>> run(const ModelView& view, const std::vector<double>& times) {
    host::Stateful<MotionRing> ring;
    REQUIRE(ring.init(view) == Status::ok);
    std::vector<std::vector<float>> out;
    for (double t : times) {
        float input[9] = {static_cast<float>(0.8 * t), static_cast<float>(0.3 * t * t), 1.0f, 0, 0, 0, 0, 0, 0};
        ring->update(view, static_cast<std::int64_t>(std::llround(t * 1e6)), input);
        out.emplace_back(input + 3, input + view.input_dim());
    }
    return out;
}

std::vector<double> clock(double rate_hz, double seconds, double jitter, double drop, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0), chance(0.0, 1.0);
    std::vector<double> times;
    for (double t = 0; t < seconds; t += 1.0 / rate_hz) {
        if (t > 0 && chance(rng) < drop) continue;
        times.push_back(std::max(0.0, t + jitter * uniform(rng) / rate_hz));
    }
    return times;
}

// Training options of a small GMM-free toy model with motion.
host::TrainingOptions toy_motion_options() {
    host::TrainingOptions options;
    options.components = 0;
    options.pca_dim = 8;
    options.velocity_weight = 1.0;
    options.velocity_span_s = 0.3;
    return options;
}

// Poses of three coordinates whose mean change from `origin` is c metres (JumpCheck's tests).
constexpr float origin[3] = {0.0f, 0.0f, 0.0f};
std::array<float, 3> shifted(float c) { return {3.0f * c, 0.0f, 0.0f}; }

}  // namespace

TEST_CASE("the velocity of a steady motion is its speed, weighted, at any frame rate, jitter or drops") {
    const ModelView view = motion_view(2.0f, 200000);
    for (const auto& times :
         {clock(30, 3, 0, 0, 1), clock(120, 3, 0, 0, 2), clock(60, 3, 0.3, 0.2, 3), clock(15, 3, 0.1, 0.1, 4)}) {
        const auto v = run(view, times);
        for (std::size_t f = 0; f < times.size(); ++f) {
            if (times[f] < 0.0999) {  // before half a span: no pose old enough
                CHECK(v[f][0] == 0.0f);
                continue;
            }
            if (times[f] < 0.1001) continue;  // the boundary itself, either way
            CAPTURE(times[f]);
            CHECK(v[f][0] == doctest::Approx(2.0 * 0.8).epsilon(1e-3));  // x moves at 0.8 m/s
            CHECK(v[f][2] == 0.0f);                                      // z stands still
            // y accelerates: its velocity is 2 · 0.3 · (the middle of the interval), within a span.
            CHECK(v[f][1] >= 2.0f * 0.6f * static_cast<float>(times[f] - 0.3) - 1e-3f);
            CHECK(v[f][1] <= 2.0f * 0.6f * static_cast<float>(times[f]) + 1e-3f);
        }
    }
}

TEST_CASE("the acceleration is the change of velocity across the span, weighted, at any timing") {
    // For x = c t² the velocity over the span's newer part minus that over its
    // older part is exactly c · a (a: the earliest pose's age), whatever the
    // middle pose's age: the ring's uneven ages divide out. Here c = 0.3 for y
    // and 0 for x and z.
    const float w = 1.5f;
    const std::uint32_t span = 200000;
    for (const float velocity : {2.0f, 0.0f}) {  // with the velocity before it, and alone
        const ModelView view = motion_view(velocity, span, w);
        REQUIRE(view.has_motion());
        REQUIRE(view.input_dim() == (velocity > 0 ? 9u : 6u));
        const std::size_t at = velocity > 0 ? 3 : 0;  // where the acceleration starts in the motion
        struct Clock {
            double rate_hz;
            std::vector<double> times;
        };
        for (const Clock& c : {Clock{30, clock(30, 3, 0, 0, 1)}, Clock{120, clock(120, 3, 0, 0, 2)},
                               Clock{60, clock(60, 3, 0.3, 0.2, 3)}, Clock{15, clock(15, 3, 0.1, 0.1, 4)}}) {
            CAPTURE(c.rate_hz);
            const std::vector<double>& times = c.times;
            const auto m = run(view, times);
            for (std::size_t f = 0; f < times.size(); ++f) {
                CAPTURE(times[f]);
                if (times[f] < 0.0999) {  // before half a span: nothing old enough
                    CHECK(m[f][at + 1] == 0.0f);
                    continue;
                }
                if (times[f] < 0.1001 || m[f][at + 1] == 0.0f) continue;  // the boundary; no middle pose yet
                const float age = m[f][at + 1] / (w * 0.3f);              // a, from y's exact value
                CHECK(age >= 0.5f * 0.2f - 1e-4f);                        // at least half the span old
                CHECK(age <= 1.5f * 0.2f + 1e-4f);                        // and within the ring
                CHECK(std::fabs(m[f][at + 0]) <= 1e-3f);                  // x moves steadily
                CHECK(m[f][at + 2] == 0.0f);                              // z stands still
            }
            // With frames every 1/120 s and no jitter, the earliest pose is a span old within a frame.
            if (c.rate_hz == 120) CHECK(m.back()[at + 1] == doctest::Approx(w * 0.3f * 0.2f).epsilon(0.05));
            // Once the ring is full, every frame has its middle pose when
            // frames come much more often than the span (not so at 15 Hz with
            // drops, where a span holds three frames).
            if (c.rate_hz >= 30)
                for (std::size_t f = 0; f < times.size(); ++f)
                    if (times[f] > 0.5) CHECK(m[f][at + 1] != 0.0f);
        }
    }
}

TEST_CASE("a restart forgets the ring, and a velocity beyond the coordinate bound is clamped") {
    const ModelView view = motion_view(1.0f, 100000);
    host::Stateful<MotionRing> ring;
    REQUIRE(ring.init(view) == Status::ok);
    float input[6] = {0, 0, 0, 0, 0, 0};
    for (int f = 0; f <= 10; ++f) {
        input[0] = 0.01f * static_cast<float>(f);
        ring->update(view, f * 20000, input);
    }
    CHECK(input[3] == doctest::Approx(0.5f).epsilon(1e-4));
    ring->reset();
    ring->update(view, 220000, input);
    CHECK(input[3] == 0.0f);  // nothing old enough after the restart
    input[0] = 1.0e4f;        // 10 km in 60 ms
    ring->update(view, 280000, input);
    CHECK(input[3] == max_pose_coordinate);
}

TEST_CASE("an acceleration beyond the coordinate bound is clamped, and zero after a restart") {
    const ModelView view = motion_view(0.0f, 100000, 1.0f);
    host::Stateful<MotionRing> ring;
    REQUIRE(ring.init(view) == Status::ok);
    float input[6] = {0, 0, 0, 0, 0, 0};
    for (int f = 0; f <= 10; ++f) ring->update(view, f * 20000, input);
    CHECK(input[3] == 0.0f);  // standing still
    input[0] = 1.0e4f;        // then 10 km in 20 ms
    ring->update(view, 220000, input);
    CHECK(input[3] == max_pose_coordinate);
    input[0] = -1.0e4f;
    ring->update(view, 240000, input);
    CHECK(input[3] == -max_pose_coordinate);
    ring->reset();
    ring->update(view, 260000, input);
    CHECK(input[3] == 0.0f);
}

TEST_CASE("a model with motion trains, and its encoder's storage holds the ring") {
    host::ToyWorld world = host::make_toy_world();
    const host::TrainingOptions options = toy_motion_options();
    const host::ModelData model = host::train_model(host::toy_clips(world, 2, 6), options);
    const ModelView view = model.view();
    CHECK(view.has_motion());
    CHECK(view.has_velocity());
    CHECK_FALSE(view.has_acceleration());
    CHECK(view.input_dim() == 2 * view.pose_dim());
    CHECK(MotionRing::required_bytes(view) >= motion_ring_poses * view.pose_dim() * sizeof(float));
    ModelView still = view;
    still.velocity_weight = 0.0f;
    CHECK(MotionRing::required_bytes(still) == 0);
    CHECK(StringEncoder::required_bytes(view) > MotionRing::required_bytes(view));
    host::Stateful<StringEncoder> encoder;
    CHECK(encoder.init(view, EncoderConfig{1000000, 0}) == Status::ok);
    // With the acceleration too the input is three poses long, and the model
    // keeps its weight through the artifact.
    host::TrainingOptions with_acceleration = options;
    with_acceleration.acceleration_weight = 0.5;
    const host::ModelData accelerating = host::train_model(host::toy_clips(world, 2, 6), with_acceleration);
    CHECK(accelerating.view().input_dim() == 3 * view.pose_dim());
    CHECK(accelerating.view().acceleration_weight == 0.5f);
    const host::ModelData back = host::parse_model("a.model", host::serialize_model(accelerating));
    CHECK(back.acceleration_weight == 0.5f);
    CHECK(host::serialize_model(back) == host::serialize_model(accelerating));
    with_acceleration.acceleration_weight = -1.0;
    CHECK_THROWS_WITH_AS(host::train_model(host::toy_clips(world, 2, 6), with_acceleration),
                         doctest::Contains("acceleration weight"), std::invalid_argument);
}

TEST_CASE("a frame's motion taken after its own keep() is the same, bit for bit") {
    // The encoder takes a frame's velocity only when its character is due,
    // which for the earlier of two frames is after that frame was kept.
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<float> noise(0.0f, 0.3f);
    for (int trial = 0; trial < 200; ++trial) {
        const auto span = static_cast<std::uint32_t>(10000 + rng() % 1990001);  // the model's bounds: 10 ms … 2 s
        // Velocity alone, acceleration alone, or both.
        const int kind = trial % 3;
        const float velocity = kind == 1 ? 0.0f : static_cast<float>(0.1 + 4.0 * unit(rng));
        const float acceleration = kind == 0 ? 0.0f : static_cast<float>(0.1 + 4.0 * unit(rng));
        const ModelView view = motion_view(velocity, span, acceleration);
        host::Stateful<MotionRing> eager, lazy;
        REQUIRE(eager.init(view) == Status::ok);
        REQUIRE(lazy.init(view) == Status::ok);
        const double rate = 5.0 + 200.0 * unit(rng);
        std::int64_t t = static_cast<std::int64_t>(rng() % 1000000);
        for (int f = 0; f < 400; ++f) {
            // Steady frames, jitter, repeated times, drops and the odd gap of several spans.
            const double u = unit(rng);
            const double step = u < 0.05 ? 0.0 : u < 0.1 ? 3.0 * span * 1e-6 * unit(rng) : (0.5 + unit(rng)) / rate;
            t += static_cast<std::int64_t>(step * 1e6);
            float a[9] = {noise(rng), noise(rng), noise(rng), 0, 0, 0, 0, 0, 0};
            float b[9] = {a[0], a[1], a[2], 9, 9, 9, 9, 9, 9};
            eager->update(view, t, a);
            lazy->keep(view, t, b);
            lazy->motion(view, t, b);
            CAPTURE(trial);
            CAPTURE(f);
            for (std::size_t i = 3; i < view.input_dim(); ++i) REQUIRE(std::memcmp(&a[i], &b[i], sizeof(float)) == 0);
        }
    }
}

TEST_CASE("the encoder's string and features equal the eagerly sampled features', frames irregular") {
    // The encoder takes velocities lazily; the trainer's sample_poses() takes
    // every frame's. Their characters, and the features the exemplars compare
    // (EncodedFrame's previous_feature / current_feature), must agree on any timing.
    for (const bool acceleration : {false, true}) {
        CAPTURE(acceleration);
        host::ToyWorld world = host::make_toy_world();
        host::TrainingOptions options = toy_motion_options();
        if (acceleration) options.acceleration_weight = 0.7;
        auto clips = host::toy_clips(world, 2, 6);
        const host::ModelData model = host::train_model(clips, options);
        const ModelView view = model.view();
        REQUIRE(view.has_motion());
        REQUIRE(view.has_acceleration() == acceleration);
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::size_t compared = 0;
        for (auto& labelled : clips) {
            host::Clip& clip = labelled.clip;
            // Re-time the clip: jitter, repeated times and a gap longer than the span.
            double t = 0.0;
            for (std::size_t f = 0; f < clip.frame_count(); ++f) {
                const double u = unit(rng);
                t += u < 0.05 ? 0.0 : u < 0.08 ? 0.5 : (0.3 + 1.4 * unit(rng)) / 60.0;
                clip.times[f] = t;
            }
            const std::vector<Character> string = host::clip_string(view, clip);
            const host::EncodedClip encoded = host::encode_clip(view, clip, true);
            REQUIRE(encoded.string == string);
            REQUIRE(encoded.features.size() == string.size() * view.feature_dim);
            CHECK(host::encode_clip(view, clip, false).features.empty());
            std::vector<float> poses;
            host::sample_poses(view, clip, 1e6 / view.string_period_us, poses);
            const std::size_t D = view.input_dim();
            REQUIRE(poses.size() == string.size() * D);
            std::vector<float> feature(view.feature_dim);
            for (std::size_t k = 0; k < string.size(); ++k) {
                REQUIRE(project_pose(view, poses.data() + k * D, feature.data()) == Status::ok);
                CHECK(descend_tree(view, feature.data()) == string[k]);
                CHECK(std::memcmp(feature.data(), &encoded.features[k * view.feature_dim],
                                  view.feature_dim * sizeof(float)) == 0);
                ++compared;
            }
        }
        CHECK(compared > 100);
    }
}

TEST_CASE("a jump: faster than the bound, and well beyond the stream's typical change") {
    JumpCheck check;
    check.configure(5.0f);
    // The first step judged sets the typical change and never jumps, however large.
    CHECK_FALSE(check.jumped(10000, shifted(0.01f).data(), origin, 3));
    for (int f = 0; f < 40; ++f) CHECK_FALSE(check.jumped(10000, shifted(0.01f).data(), origin, 3));  // 1 m/s
    // 10 m/s, ten times the typical change: a jump. It does not move the typical
    // change, so a 2 m/s step after it is none.
    CHECK(check.jumped(10000, shifted(0.1f).data(), origin, 3));
    CHECK_FALSE(check.jumped(10000, shifted(0.02f).data(), origin, 3));
    // One instant judges nothing.
    CHECK_FALSE(check.jumped(0, shifted(1.0f).data(), origin, 3));
    // A jittery clock: 2 cm 1 ms after the last frame is 2 m/s over the typical
    // 10 ms interval, though it would be 20 m/s over 1 ms.
    CHECK_FALSE(check.jumped(1000, shifted(0.02f).data(), origin, 3));
    // A dropped frame: 12 cm over 30 ms is 4 m/s.
    CHECK_FALSE(check.jumped(30000, shifted(0.12f).data(), origin, 3));
    // A noisy sensor: every frame changes by 6 cm in 10 ms (6 m/s, over the bound),
    // so none of them is a jump; 30 cm, five times as much, is.
    check.reset();
    for (int f = 0; f < 40; ++f) CHECK_FALSE(check.jumped(10000, shifted(0.06f).data(), origin, 3));
    CHECK_FALSE(check.jumped(10000, shifted(0.15f).data(), origin, 3));  // 2.5 times: not yet
    CHECK(check.jumped(10000, shifted(0.3f).data(), origin, 3));
    // 0 never jumps.
    check.configure(0.0f);
    CHECK_FALSE(check.jumped(10000, shifted(0.01f).data(), origin, 3));
    CHECK_FALSE(check.jumped(10000, shifted(100.0f).data(), origin, 3));
}

TEST_CASE("the default bound sees a joining at 30 Hz as at 120 Hz") {
    // A joining moves the pose by a distance, not a speed: 15 cm on average
    // shows 18 m/s between frames at 120 Hz but 4.5 m/s at 30 Hz, which the
    // 8 m/s bound of before missed (models/README.md, "The jump bound at any
    // frame rate"). Real movement, 1 m/s at either rate, is no jump.
    for (const std::int64_t step_us : {std::int64_t{8333}, std::int64_t{33333}}) {
        CAPTURE(step_us);
        const float per_frame = 1.0f * static_cast<float>(step_us) * 1e-6f;  // 1 m/s
        JumpCheck check;
        check.configure(default_max_pose_speed);
        for (int f = 0; f < 40; ++f) CHECK_FALSE(check.jumped(step_us, shifted(per_frame).data(), origin, 3));
        CHECK(check.jumped(step_us, shifted(0.15f).data(), origin, 3));
        JumpCheck before;
        before.configure(8.0f);
        for (int f = 0; f < 40; ++f) CHECK_FALSE(before.jumped(step_us, shifted(per_frame).data(), origin, 3));
        CHECK(before.jumped(step_us, shifted(0.15f).data(), origin, 3) == (step_us < 20000));
    }
}

TEST_CASE("the encoder starts the motion again at a jump, as a stream starting there would") {
    host::ToyWorld world = host::make_toy_world();
    const host::ModelData model = host::train_model(host::toy_clips(world, 2, 6), toy_motion_options());
    const ModelView view = model.view();
    REQUIRE(view.has_velocity());
    // A stream of one toy performance, then the same again with every joint
    // but the root moved 30 units up (the tracker jumped; the pose it reports
    // moves as before), a frame per string period, so every frame gives a
    // character, on the same frames as when the second part streams alone.
    const host::LabelledClip performance = host::toy_clips(world, 1, 3).front();
    const host::Clip& clip = performance.clip;
    const std::size_t J = clip.joint_count(), F = clip.frame_count();
    REQUIRE(clip.roles.root >= 0);
    const auto root = static_cast<std::size_t>(clip.roles.root), up = static_cast<std::size_t>(clip.up_axis);
    std::vector<float> frames(clip.positions);
    for (std::size_t f = 0; f < F; ++f) {
        const float* p = clip.frame(f);
        for (std::size_t j = 0; j < J; ++j)
            for (std::size_t k = 0; k < 3; ++k) frames.push_back(p[3 * j + k] + (j != root && k == up ? 30.0f : 0.0f));
    }
    const std::int64_t step = view.string_period_us;
    // The bound between the fastest the normalised pose moves within either part
    // and how fast it moves at the jump, each the mean over its coordinates (the
    // toy's units are its own).
    std::vector<float> pose(view.input_dim()), before(view.input_dim()), skeleton(3 * J);
    float within = 0.0f, jump = 0.0f;
    for (std::size_t f = 0; f < 2 * F; ++f) {
        REQUIRE(normalize_pose(view, &frames[f * 3 * J], pose.data(), skeleton.data()) == Status::ok);
        float moved = 0.0f;
        for (std::size_t i = 0; f > 0 && i < view.pose_dim(); ++i) moved += std::fabs(pose[i] - before[i]);
        moved /= static_cast<float>(view.pose_dim());
        float& fastest = f == F ? jump : within;
        fastest = std::max(fastest, moved / (static_cast<float>(step) * 1e-6f));
        before = pose;
    }
    REQUIRE(jump > 2.0f * within);
    const float bound = std::sqrt(jump * within);
    auto encode = [&](float max_speed, std::size_t first) {
        host::Stateful<StringEncoder> encoder;
        EncoderConfig config;
        config.max_pose_speed = max_speed;
        REQUIRE(encoder.init(view, config) == Status::ok);
        std::vector<std::vector<float>> velocities;
        std::vector<std::size_t> restarts;
        for (std::size_t f = first; f < 2 * F; ++f) {
            const EncodedFrame e = encoder->push_frame(static_cast<std::int64_t>(f) * step, &frames[f * 3 * J]);
            REQUIRE(e.accepted());
            if (e.motion_restarted) restarts.push_back(f);
            velocities.emplace_back();
            if (e.from_current > 0)
                velocities.back().assign(e.current_pose + view.pose_dim(), e.current_pose + view.input_dim());
        }
        return std::make_pair(velocities, restarts);
    };
    const auto [joined, restarts] = encode(bound, 0);
    const auto [alone, alone_restarts] = encode(bound, F);
    const auto [across_jump, never] = encode(0.0f, 0);
    // The bound restarts the motion at the moved pose's first frame, and nowhere else.
    REQUIRE(restarts == std::vector<std::size_t>{F});
    CHECK(alone_restarts.empty());
    CHECK(never.empty());
    // From there on the joined stream's velocities are the moved pose's
    // alone, bit for bit; without the bound they difference across the jump.
    std::size_t compared = 0, differ = 0;
    for (std::size_t f = F; f < 2 * F; ++f) {
        const std::vector<float>& v = joined[f];
        REQUIRE(v.empty() == alone[f - F].empty());
        if (v.empty()) continue;
        CHECK(std::memcmp(v.data(), alone[f - F].data(), v.size() * sizeof(float)) == 0);
        differ += across_jump[f] != v;
        ++compared;
    }
    CHECK(compared >= F - 1);
    CHECK(differ > 0);
    // A negative or NaN bound is refused.
    host::Stateful<StringEncoder> refused;
    EncoderConfig negative;
    negative.max_pose_speed = -1.0f;
    CHECK(refused.init(view, negative) == Status::invalid_argument);
    negative.max_pose_speed = std::nanf("");
    CHECK(refused.init(view, negative) == Status::invalid_argument);
}
