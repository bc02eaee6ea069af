// The clip's motion directions: the sectors, the histograms by hand, their
// independence of the facing, and training's classifier over them
// (descriptor.hpp's clip_directions() and direction_penalties(),
// src/train/descriptor.*).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <string>
#include <vector>

#include "actionstring/clip.hpp"
#include "actionstring/descriptor.hpp"
#include "model/artifact.hpp"
#include "model/blob.hpp"
#include "model/header.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "toy/toy.hpp"
#include "clip_records.hpp"
#include "toy_options.hpp"
#include "train/descriptor.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

// Records of one joint (3 pose floats, then the facing {cos, sin}) from its
// positions as faced at the first record, each record's pose turned by its
// own facing angle about y (up axis 1), as normalize_pose() leaves it.
std::vector<float> records_of(const std::vector<std::array<float, 3>>& positions, const std::vector<float>& angles) {
    std::vector<float> out;
    for (std::size_t t = 0; t < positions.size(); ++t) {
        // The body faced θ_t; normalize_pose() took θ_t out. Here the clip's
        // positions are given in record 0's frame, so the pose is turned by θ_t − θ_0 less.
        const float c = std::cos(angles[t] - angles[0]), s = std::sin(angles[t] - angles[0]);
        const std::array<float, 3>& p = positions[t];
        // Up axis y: h1 = z, h2 = x; normalize_pose's turn by −φ: (h1, h2) → (c h1 + s h2, −s h1 + c h2).
        const float h1 = c * p[2] + s * p[0], h2 = -s * p[2] + c * p[0];
        out.insert(out.end(), {h2, p[1], h1, std::cos(angles[t]), std::sin(angles[t])});
    }
    return out;
}

ModelData directed_model(const std::vector<LabelledClip>& train, bool reject = false) {
    TrainingOptions options = test::toy_options();
    options.components = 0;
    options.pca_dim = 6;
    options.epsilon = 0.5;
    options.sigma = 0.5;
    options.direction_levels = 2;
    options.direction_ridge = 100.0;
    options.direction_weight = 2.0;
    options.reject = reject;
    return train_model(train, options);
}

// A clip turned about its up axis (y) by `angle`, about the origin.
Clip turned_clip(const Clip& clip, float angle) {
    Clip out = clip;
    const float c = std::cos(angle), s = std::sin(angle);
    for (std::size_t f = 0; f < out.frame_count(); ++f)
        for (std::size_t j = 0; j < out.joint_count(); ++j) {
            float* p = &out.positions[(f * out.joint_count() + j) * 3];
            const float x = p[0], z = p[2];
            p[0] = c * x + s * z;
            p[2] = -s * x + c * z;
        }
    return out;
}

}  // namespace

TEST_CASE("directions: a step's sector by comparisons, eight of 45 degrees counter-clockwise from +u") {
    CHECK(direction_sector(1.0f, 0.0f) == 0u);
    CHECK(direction_sector(1.0f, 0.5f) == 0u);
    CHECK(direction_sector(1.0f, 1.0f) == 1u);  // on a boundary: the sector counter-clockwise of it
    CHECK(direction_sector(0.5f, 1.0f) == 1u);
    CHECK(direction_sector(0.0f, 1.0f) == 2u);
    CHECK(direction_sector(-0.5f, 1.0f) == 2u);
    CHECK(direction_sector(-1.0f, 0.5f) == 3u);
    CHECK(direction_sector(-1.0f, 0.0f) == 3u);
    CHECK(direction_sector(-1.0f, -0.5f) == 4u);
    CHECK(direction_sector(-0.5f, -1.0f) == 5u);
    CHECK(direction_sector(0.0f, -1.0f) == 6u);
    CHECK(direction_sector(0.5f, -1.0f) == 6u);
    CHECK(direction_sector(1.0f, -0.5f) == 7u);
    CHECK(direction_sector(0.0f, 0.0f) == 3u);  // no step: its length adds nothing anyway
    // Every sector is reached by the angle it names.
    for (int k = 0; k < 8; ++k) {
        const double angle = (k + 0.5) * 3.14159265358979 / 4.0;
        CHECK(direction_sector(static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle))) ==
              static_cast<std::size_t>(k));
    }
}

TEST_CASE("directions: the histograms by hand, part by part, normalised, zero where nothing moves") {
    // One joint, up axis y, facing never turning: +x for three steps, then +y for two, twice as long.
    const std::vector<std::array<float, 3>> path = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {3, 2, 0}, {3, 4, 0}};
    const std::vector<float> records = records_of(path, std::vector<float>(path.size(), 0.3f));
    constexpr std::size_t bins = ModelView::direction_bins;
    std::vector<float> out(descriptor_parts(2) * 3 * bins, -1.0f);
    clip_directions(records.data(), path.size(), 1, 1, 2, out.data());
    // Level 1, the whole clip: in xy, 3 of length along +x (sector 0) and 4 along +y (sector 2).
    const float* xy = out.data();
    const float* yz = xy + bins;
    const float* xz = yz + bins;
    CHECK(xy[0] == doctest::Approx(3.0 / 7.0));
    CHECK(xy[2] == doctest::Approx(4.0 / 7.0));
    // yz: the +y steps are (u, v) = (dy, dz) = (2, 0), sector 0; the +x steps have no length there.
    CHECK(yz[0] == doctest::Approx(1.0));
    // xz: the +x steps (dx, dz) = (1, 0), sector 0; the +y steps none.
    CHECK(xz[0] == doctest::Approx(1.0));
    float total = 0.0f;
    for (std::size_t k = 0; k < 3 * bins; ++k) total += out[k];
    CHECK(total == doctest::Approx(3.0));
    // Level 2: records [0, 3) take the steps 0→1, 1→2 (+x only); [3, 6) take 2→3, 3→4, 4→5.
    const float* first = out.data() + 3 * bins;
    const float* second = first + 3 * bins;
    CHECK(first[0] == doctest::Approx(1.0));
    CHECK(first[bins + 0] == 0.0f);  // yz: nothing moved there, left 0
    CHECK(second[0] == doctest::Approx(1.0 / 5.0));
    CHECK(second[2] == doctest::Approx(4.0 / 5.0));
    // Fewer than two records: no step, all zero; null in, nothing read.
    std::vector<float> none(3 * bins, -1.0f);
    clip_directions(records.data(), 1, 1, 1, 1, none.data());
    CHECK(std::all_of(none.begin(), none.end(), [](float v) { return v == 0.0f; }));
    clip_directions(nullptr, 6, 1, 1, 1, none.data());
    CHECK(std::all_of(none.begin(), none.end(), [](float v) { return v == 0.0f; }));
    clip_directions(records.data(), 6, 1, 1, 1, nullptr);  // nothing to write: no crash
}

TEST_CASE("directions: each pose is turned back to the clip's first facing, so a facing that jitters changes nothing") {
    // A joint circling in the horizontal plane while rising; the body's
    // facing wanders a few degrees from frame to frame, as a tracked hip line does.
    std::vector<std::array<float, 3>> path;
    std::vector<float> steady, jittery;
    for (int t = 0; t < 40; ++t) {
        const float a = 0.2f * static_cast<float>(t);
        path.push_back({std::cos(a), 0.05f * static_cast<float>(t), std::sin(a)});
        steady.push_back(1.1f);
        jittery.push_back(1.1f + 0.08f * std::sin(1.7f * static_cast<float>(t)) + (t % 3 == 0 ? 0.05f : -0.03f));
    }
    const std::vector<float> a = records_of(path, steady), b = records_of(path, jittery);
    REQUIRE(a != b);  // the poses as normalize_pose() leaves them differ
    constexpr std::size_t size = descriptor_parts(3) * 3 * ModelView::direction_bins;
    std::vector<float> ha(size), hb(size);
    clip_directions(a.data(), path.size(), 1, 1, 3, ha.data());
    clip_directions(b.data(), path.size(), 1, 1, 3, hb.data());
    for (std::size_t k = 0; k < size; ++k) CHECK(hb[k] == doctest::Approx(ha[k]).epsilon(1e-4));
}

TEST_CASE("directions: a clip performed facing elsewhere has the same histograms, through the encoder") {
    const ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 6, 100);
    const ModelData model = directed_model(train);
    const ModelView view = model.view();
    REQUIRE(view.has_directions());
    const auto held_out = toy_clips(world, 2, 9000, 30.0);
    for (const LabelledClip& c : held_out) {
        const EncodedClip a = encode_clip(view, c.clip, true, true);
        const EncodedClip b = encode_clip(view, turned_clip(c.clip, 1.2f), true, true);
        REQUIRE(a.string.size() == b.string.size());
        REQUIRE(a.records.size() == a.string.size() * view.direction_record_floats());
        std::vector<float> ha(view.direction_size()), hb(view.direction_size());
        clip_directions(a.records.data(), a.string.size(), view.pose_joint_count, view.up_axis, view.direction_levels,
                        ha.data());
        clip_directions(b.records.data(), b.string.size(), view.pose_joint_count, view.up_axis, view.direction_levels,
                        hb.data());
        for (std::size_t k = 0; k < ha.size(); ++k) CHECK(hb[k] == doctest::Approx(ha[k]).epsilon(1e-3).scale(1.0));
    }
}

TEST_CASE("directions: penalties relative to the best label, validation, no opinion without records") {
    const ToyWorld world = make_toy_world();
    const ModelData model = directed_model(toy_clips(world, 6, 100));
    const ModelView view = model.view();
    REQUIRE(validate_model(view) == Status::ok);
    const auto held_out = toy_clips(world, 1, 9000, 30.0);
    const EncodedClip encoded = encode_clip(view, held_out.front().clip, true, true);
    const std::size_t n = encoded.string.size(), L = view.label_count;
    std::vector<float> scratch(view.direction_size()), penalties(L, -1.0f);
    direction_penalties(view, encoded.records.data(), n, scratch.data(), penalties.data());
    CHECK(*std::min_element(penalties.begin(), penalties.end()) == 0.0f);
    CHECK(*std::max_element(penalties.begin(), penalties.end()) > 0.0f);
    // By hand: weight × (best score − score).
    std::vector<float> h(view.direction_size()), scores(L);
    clip_directions(encoded.records.data(), n, view.pose_joint_count, view.up_axis, view.direction_levels, h.data());
    for (std::size_t l = 0; l < L; ++l) {
        float sum = view.direction_bias[l];
        for (std::size_t p = 0; p < h.size(); ++p) sum += view.direction_weights[l * h.size() + p] * h[p];
        scores[l] = sum;
    }
    const float best = *std::max_element(scores.begin(), scores.end());
    for (std::size_t l = 0; l < L; ++l) CHECK(penalties[l] == view.direction_weight * (best - scores[l]));
    // Without records, without a clip or without the model's directions: no opinion.
    direction_penalties(view, nullptr, n, scratch.data(), penalties.data());
    CHECK(std::all_of(penalties.begin(), penalties.end(), [](float v) { return v == 0.0f; }));
    direction_penalties(view, encoded.records.data(), 0, scratch.data(), penalties.data());
    CHECK(std::all_of(penalties.begin(), penalties.end(), [](float v) { return v == 0.0f; }));
    ModelView off = view;
    off.direction_weight = 0.0f;
    direction_penalties(off, encoded.records.data(), n, scratch.data(), penalties.data());
    CHECK(std::all_of(penalties.begin(), penalties.end(), [](float v) { return v == 0.0f; }));
    // A model the runtime could not use is refused, with the field.
    const char* problem = nullptr;
    ModelView bad = view;
    bad.direction_levels = 9;
    CHECK(validate_model(bad, &problem) == Status::invalid_model);
    CHECK(std::string(problem) == "direction_levels: more than 8");
    bad = view;
    bad.direction_weight = -1.0f;
    CHECK(validate_model(bad, &problem) == Status::invalid_model);
    bad = view;
    bad.direction_weights = nullptr;
    CHECK(validate_model(bad, &problem) == Status::invalid_model);
    CHECK(std::string(problem) == "direction_weights: missing, non-finite or beyond 1e6");
    std::vector<float> huge(model.direction_weights);
    huge[3] = std::numeric_limits<float>::infinity();
    bad = view;
    bad.direction_weights = huge.data();
    CHECK(validate_model(bad, &problem) == Status::invalid_model);
}

TEST_CASE("directions: trained into a model, stored, read back, in the header and the blob, used by clips") {
    const ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 6, 100);
    const auto held_out = toy_clips(world, 5, 9000, 30.0);
    const ModelData model = directed_model(train);
    const ModelView view = model.view();
    REQUIRE(view.has_directions());
    CHECK(view.direction_levels == 2);
    CHECK(model.direction_weights.size() == view.label_count * 3u * view.pose_joint_count * 3u * 8u);
    CHECK(model.direction_bias.size() == view.label_count);
    // Deterministic, and through the artifact, the header and the blob.
    const std::string text = serialize_model(model);
    CHECK(serialize_model(directed_model(train)) == text);
    CHECK(serialize_model(parse_model("x.model", text)) == text);
    const std::string header = generate_header(model, artifact_checksum(text), "toy", "toy.model");
    CHECK(header.find("m.direction_levels = 2;") != std::string::npos);
    CHECK(header.find("m.direction_weights = kDirectionWeights;") != std::string::npos);
    const ModelData from_blob = read_blob("toy.blob", write_blob(model));
    REQUIRE(from_blob.view().has_directions());
    CHECK(serialize_model(from_blob) == text);
    // Clip classification adds the penalties: the winner's distance grew by exactly its own.
    CHECK(clip_accuracy(view, held_out) >= 0.9);
    for (const LabelledClip& c : held_out) {
        const EncodedClip encoded = encode_clip(view, c.clip, true, true);
        const std::vector<float> penalties = clip_descriptor_penalties(view, encoded.features, encoded.records);
        CHECK(*std::min_element(penalties.begin(), penalties.end()) == 0.0f);
        const Classification with = classify_string(view, encoded.string, {}, nullptr, penalties.data());
        CHECK(with.label == classify_clip(view, c.clip).label);
        const Classification without = classify_string(view, encoded.string);
        if (with.label == without.label && with.representative == without.representative)
            CHECK(with.distance == doctest::Approx(without.distance + penalties[with.label]));
    }
    // With learned rejection the samples carry their records (spliced with their
    // characters), measured by classifiers fitted without their subjects.
    const ModelData rejecting = directed_model(train, true);
    REQUIRE(rejecting.view().has_directions());
    REQUIRE(rejecting.has_label_bounds == 1);
    CHECK(serialize_model(directed_model(train, true)) == serialize_model(rejecting));
    CHECK(clip_accuracy(rejecting.view(), held_out) >= 0.8);
}

TEST_CASE("directions: the fit refuses what it cannot use, and levels or weight 0 mean none") {
    const ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 3, 100);
    const ModelData reference = directed_model(train);
    const auto [records, labels] = test::clip_records(reference, train);
    ModelData m = parse_model("copy.model", serialize_model(reference));
    set_directions(m, records, labels, 2, 100.0, 2.0);
    CHECK(m.direction_weights == reference.direction_weights);  // what training fitted
    CHECK(m.direction_bias == reference.direction_bias);
    set_directions(m, records, labels, 0, 100.0, 2.0);
    CHECK_FALSE(m.view().has_directions());
    CHECK(m.direction_weights.empty());
    set_directions(m, records, labels, 2, 100.0, 0.0);
    CHECK(m.direction_levels == 0);
    CHECK_THROWS_AS(set_directions(m, records, labels, 9, 100.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(set_directions(m, records, labels, 2, 0.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(set_directions(m, {records[0]}, {labels[0]}, 2, 100.0, 1.0), std::invalid_argument);
    ModelData no_pose;
    no_pose.label_names = reference.label_names;
    CHECK_THROWS_WITH_AS(set_directions(no_pose, records, labels, 2, 100.0, 1.0), doctest::Contains("pose joints"),
                         std::invalid_argument);
    // Clips labelled unknown are left out; a refusal leaves the model without directions.
    std::vector<LabelId> unknown(labels.size(), unknown_label);
    CHECK_THROWS_AS(set_directions(m, records, unknown, 2, 100.0, 1.0), std::invalid_argument);
    CHECK_FALSE(m.view().has_directions());
}
