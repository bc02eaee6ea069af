// The motion directions of a stream's last characters in the segmenter:
// the penalties by hand, the fit, the model's fields through every form,
// the segmenter's window and its restart at a jump, and the annotator spread
// or not (descriptor.hpp's window_direction_penalties(), segmenter.hpp,
// src/train/descriptor.*).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/descriptor.hpp"
#include "actionstring/encoder.hpp"
#include "actionstring/segmenter.hpp"
#include "model/artifact.hpp"
#include "model/blob.hpp"
#include "model/header.hpp"
#include "run/encode.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"
#include "clip_records.hpp"
#include "toy_options.hpp"
#include "train/descriptor.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

TrainingOptions window_options() {
    TrainingOptions options = test::toy_options();
    options.components = 0;
    options.pca_dim = 6;
    options.epsilon = 0.5;
    options.sigma = 0.5;
    options.velocity_weight = 1.0;  // motion, so the encoder judges jumps
    options.velocity_span_s = 0.2;
    options.direction_window_s = 1.0;  // 10 characters at 10 Hz
    options.direction_window_ridge = 100.0;
    options.online.direction_weight = 0.5f;
    return options;
}

// Each label's penalty by hand: weight × (best score − score) over the one-level histograms.
std::vector<float> by_hand(const ModelView& view, const float* records, std::size_t n, float weight) {
    const std::size_t L = view.label_count, P = view.window_direction_size();
    std::vector<float> h(P), scores(L), out(L, 0.0f);
    if (n < 2) return out;
    clip_directions(records, n, view.pose_joint_count, view.up_axis, 1, h.data());
    for (std::size_t l = 0; l < L; ++l) {
        float sum = view.window_direction_bias[l];
        for (std::size_t p = 0; p < P; ++p) sum += view.window_direction_weights[l * P + p] * h[p];
        scores[l] = sum;
    }
    const float best = *std::max_element(scores.begin(), scores.end());
    for (std::size_t l = 0; l < L; ++l) out[l] = weight * (best - scores[l]);
    return out;
}

bool all_zero(const float* v, std::size_t n) {
    return std::all_of(v, v + n, [](float x) { return x == 0.0f; });
}

}  // namespace

TEST_CASE("window directions: penalties by hand, none before a step or without the window, validation") {
    const ToyWorld world = make_toy_world();
    const ModelData model = train_model(toy_clips(world, 6, 100), window_options());
    const ModelView view = model.view();
    REQUIRE(validate_model(view) == Status::ok);
    REQUIRE(view.has_window_directions());
    CHECK(view.window_direction_chars == 10);
    CHECK(view.window_direction_size() == view.pose_joint_count * 3u * 8u);
    CHECK(segmenter_config(view).direction_weight == 0.5f);
    const auto held_out = toy_clips(world, 1, 9000, 30.0);
    const EncodedClip encoded = encode_clip(view, held_out.front().clip, false, true);
    const std::size_t width = view.direction_record_floats(), L = view.label_count;
    REQUIRE(encoded.records.size() >= 12 * width);
    std::vector<float> scratch(view.window_direction_size()), penalties(L, -1.0f);
    for (const std::size_t n : {2u, 5u, 10u}) {
        window_direction_penalties(view, encoded.records.data() + width, n, 0.5f, scratch.data(), penalties.data());
        CHECK(penalties == by_hand(view, encoded.records.data() + width, n, 0.5f));
        CHECK(*std::min_element(penalties.begin(), penalties.end()) == 0.0f);
    }
    CHECK(*std::max_element(penalties.begin(), penalties.end()) > 0.0f);
    // One record is no step; no records, no window in the model: no opinion.
    window_direction_penalties(view, encoded.records.data(), 1, 0.5f, scratch.data(), penalties.data());
    CHECK(all_zero(penalties.data(), L));
    window_direction_penalties(view, nullptr, 5, 0.5f, scratch.data(), penalties.data());
    CHECK(all_zero(penalties.data(), L));
    ModelView off = view;
    off.window_direction_chars = 0;
    window_direction_penalties(off, encoded.records.data(), 5, 0.5f, scratch.data(), penalties.data());
    CHECK(all_zero(penalties.data(), L));
    // A model the runtime could not use is refused, with the field.
    const char* problem = nullptr;
    ModelView bad = view;
    bad.window_direction_weights = nullptr;
    CHECK(validate_model(bad, &problem) == Status::invalid_model);
    CHECK(std::string(problem) == "window_direction_weights: missing, non-finite or beyond 1e6");
    std::vector<float> huge(model.window_direction_bias);
    huge[0] = std::nanf("");
    bad = view;
    bad.window_direction_bias = huge.data();
    CHECK(validate_model(bad, &problem) == Status::invalid_model);
    CHECK(std::string(problem) == "window_direction_bias: missing, non-finite or beyond 1e6");
    // A setting the segmenter cannot use is refused.
    SegmenterConfig config = segmenter_config(view);
    config.direction_weight = -1.0f;
    CHECK(ActionSegmenter::check(view, config) == Status::invalid_argument);
    config.direction_weight = std::nanf("");
    CHECK(ActionSegmenter::check(view, config) == Status::invalid_argument);
}

TEST_CASE("window directions: trained deterministically, through the artifact, the header and the blob") {
    const ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 6, 100);
    const ModelData model = train_model(train, window_options());
    CHECK(model.window_direction_weights.size() == model.view().label_count * model.view().window_direction_size());
    CHECK(model.window_direction_bias.size() == model.view().label_count);
    const std::string text = serialize_model(model);
    CHECK(serialize_model(train_model(train, window_options())) == text);
    CHECK(serialize_model(parse_model("x.model", text)) == text);
    const std::string header = generate_header(model, artifact_checksum(text), "toy", "toy.model");
    CHECK(header.find("m.window_direction_chars = 10;") != std::string::npos);
    CHECK(header.find("m.window_direction_weights = kWindowDirectionWeights;") != std::string::npos);
    const ModelData from_blob = read_blob("toy.blob", write_blob(model));
    REQUIRE(from_blob.view().has_window_directions());
    CHECK(serialize_model(from_blob) == text);
}

TEST_CASE("window directions: the fit refuses what it cannot use, and a window of 0 means none") {
    const ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 3, 100);
    const ModelData reference = train_model(train, window_options());
    const auto [records, labels] = test::clip_records(reference, train);
    ModelData m = parse_model("copy.model", serialize_model(reference));
    set_window_directions(m, records, labels, 10, 100.0);
    CHECK(m.window_direction_weights == reference.window_direction_weights);  // what training fitted
    CHECK(m.window_direction_bias == reference.window_direction_bias);
    set_window_directions(m, records, labels, 0, 100.0);
    CHECK_FALSE(m.view().has_window_directions());
    CHECK(m.window_direction_weights.empty());
    CHECK_THROWS_AS(set_window_directions(m, records, labels, 1, 100.0), std::invalid_argument);
    CHECK_THROWS_AS(set_window_directions(m, records, labels, 1025, 100.0), std::invalid_argument);
    CHECK_THROWS_AS(set_window_directions(m, records, labels, 10, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(set_window_directions(m, records, std::vector<LabelId>(labels.size(), unknown_label), 10, 100.0),
                    std::invalid_argument);
    ModelData no_pose;
    no_pose.label_names = reference.label_names;
    CHECK_THROWS_WITH_AS(set_window_directions(no_pose, records, labels, 10, 100.0), doctest::Contains("pose joints"),
                         std::invalid_argument);
}

TEST_CASE("window directions: the segmenter scores its last characters and starts them again when told") {
    const ToyWorld world = make_toy_world();
    const ModelData model = train_model(toy_clips(world, 6, 100), window_options());
    const ModelView view = model.view();
    const auto held_out = toy_clips(world, 2, 9000, 30.0);
    Clip joined = held_out.front().clip;  // two clips back to back: a string long enough to fill the window
    const EncodedClip encoded = encode_clip(view, joined, true, true);
    const std::size_t width = view.direction_record_floats(), D = view.pose_dim(), L = view.label_count;
    const std::size_t n = encoded.string.size(), N = view.window_direction_chars;
    REQUIRE(n > N + 2);
    const SegmenterConfig config = segmenter_config(view);
    Stateful<ActionSegmenter> segmenter;
    REQUIRE(segmenter.init(view, config) == Status::ok);
    const std::size_t restart_at = N + 1;
    for (std::size_t t = 0; t < n; ++t) {
        CAPTURE(t);
        if (t == restart_at) segmenter->restart_window();
        const float* record = encoded.records.data() + t * width;
        segmenter->push(encoded.string[t], encoded.features.data() + t * view.feature_dim, record, record + D);
        const float* costs = segmenter->window_costs();
        REQUIRE(costs != nullptr);
        // The window: the last N records, none before the restart.
        const std::size_t first_allowed = t >= restart_at ? restart_at : 0;
        const std::size_t first = std::max(first_allowed, t + 1 > N ? t + 1 - N : std::size_t{0});
        const std::vector<float> expected =
            by_hand(view, encoded.records.data() + first * width, t + 1 - first, config.direction_weight);
        CHECK(std::vector<float>(costs, costs + L) == expected);
    }
    // A character without its pose adds nothing; weight 0 keeps no window at all.
    segmenter->push(encoded.string[0], encoded.features.data());
    CHECK(all_zero(segmenter->window_costs(), L));
    SegmenterConfig off = config;
    off.direction_weight = 0.0f;
    Stateful<ActionSegmenter> plain;
    REQUIRE(plain.init(view, off) == Status::ok);
    CHECK(plain->window_costs() == nullptr);
    CHECK(ActionSegmenter::required_bytes(view, off) < ActionSegmenter::required_bytes(view, config));
}

TEST_CASE("window directions: a jump starts a new epoch, and the annotator's labels are the same spread or not") {
    const ToyWorld world = make_toy_world();
    const ModelData model = train_model(toy_clips(world, 6, 100), window_options());
    const ModelView view = model.view();
    // Two streams joined, the second with both hands a metre higher: the pose
    // jumps where they meet (4.5 m/s at 30 Hz, over the default bound).
    ToyStreamOptions first_options, second_options;
    second_options.seed = 7;
    std::vector<ToyFrame> frames = toy_stream(world, {0, 1}, first_options);
    const std::vector<ToyFrame> second = toy_stream(world, {3, 2}, second_options);
    const std::size_t joint = frames.size();
    const std::int64_t offset = frames.back().time_us + 33333 - second.front().time_us;
    for (ToyFrame f : second) {
        f.time_us += offset;
        for (const std::size_t hand : {3u, 4u}) f.positions[hand * 3 + 1] += 1.0f;
        frames.push_back(f);
    }
    // The encoder counts the jumps: every pose after one is of a later epoch.
    Stateful<StringEncoder> encoder;
    EncoderConfig stream;  // a stream's jump bound (an encoder's default, 0, takes a clip as recorded)
    stream.max_pose_speed = default_max_pose_speed;
    REQUIRE(encoder.init(view, stream) == Status::ok);
    std::uint32_t jumps = 0;
    bool at_joint = false;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const EncodedFrame e = encoder->push_frame(frames[i].time_us, frames[i].positions.data());
        REQUIRE(e.accepted());
        const std::uint32_t before = jumps;  // the previous frame's pose's epoch
        if (e.motion_restarted) ++jumps, at_joint = at_joint || i == joint;
        if (e.from_previous > 0) CHECK(e.previous_epoch == before);
        if (e.from_current > 0) CHECK(e.current_epoch == jumps);
    }
    CHECK(at_joint);
    // The annotator restarts the window at each epoch, spread or not: the same labels.
    const auto settled = [&](bool spread) {
        AnnotatorConfig config = annotator_config(view);
        config.spread_work = spread;
        Stateful<Annotator> annotator;
        REQUIRE(annotator.init(view, config) == Status::ok);
        std::vector<std::pair<std::uint64_t, LabelId>> out;
        const auto take = [&](const FrameResult& r) {
            for (std::uint32_t k = 0; k < r.characters_settled; ++k) {
                const std::uint64_t c = annotator->settled_character() - (r.characters_settled - 1 - k);
                out.emplace_back(c, annotator->settled_label(c));
            }
        };
        for (const ToyFrame& f : frames) take(annotator->push_frame(f.time_us, f.positions.data()));
        take(annotator->finish_work());
        return out;
    };
    const auto plain = settled(false), spread = settled(true);
    CHECK(plain.size() > 40);
    CHECK(plain == spread);
}
