// Model validation: every corrupted table is refused before it reaches the per-frame code.
#include <doctest/doctest.h>

#include <functional>
#include <limits>

#include "actionstring/annotator.hpp"
#include "toy/toy.hpp"

using namespace actionstring;

namespace {
using TestLimits = host::ToyLimits;
using Cap = host::ToyCapacity;
// One bound too small each.
struct FewJoints : TestLimits {
    static constexpr std::size_t joints = 4;
};
struct FewComponents : TestLimits {
    static constexpr std::size_t components = 4;
};
struct FewRepresentatives : TestLimits {
    static constexpr std::size_t representatives = 2;
};
struct FewRepresentativeChars : TestLimits {
    static constexpr std::size_t representative_chars = 50;
};
struct FewWindows : TestLimits {
    static constexpr std::size_t windows = 2;
};
struct EnoughWindows : TestLimits {
    static constexpr std::size_t windows = 4;
};
const float kNaN = std::numeric_limits<float>::quiet_NaN();
}  // namespace

TEST_CASE("the toy model is valid") {
    host::ToyWorld world = host::make_toy_world();
    CHECK(validate_model(world.model.view()) == Status::ok);
}

TEST_CASE("each kind of corruption is refused") {
    const std::vector<std::pair<const char*, std::function<void(host::ModelData&)>>> corruptions = {
        {"root out of range", [](host::ModelData& m) { m.root_joint = 9; }},
        {"hips equal", [](host::ModelData& m) { m.right_hip_joint = m.left_hip_joint; }},
        {"up axis", [](host::ModelData& m) { m.up_axis = 3; }},
        {"pose joint out of range", [](host::ModelData& m) { m.pose_joints[1] = 5; }},
        {"no pose joints", [](host::ModelData& m) { m.pose_joints.clear(); }},
        {"bad scale",
         [](host::ModelData& m) {
             m.scale_mode = ScaleMode::hip_width;
             m.reference_scale = 0;
         }},
        {"feature dim", [](host::ModelData& m) { m.feature_dim = 11; }},
        {"NaN mean", [](host::ModelData& m) { m.gmm_means[3] = kNaN; }},
        {"NaN factor", [](host::ModelData& m) { m.gmm_factors.back() = kNaN; }},
        {"inf log weight", [](host::ModelData& m) { m.gmm_log_weights[0] = -std::numeric_limits<float>::infinity(); }},
        {"NaN centroid", [](host::ModelData& m) { m.node_centroids[0] = kNaN; }},
        {"child points back", [](host::ModelData& m) { m.node_children[2] = 0; }},
        {"child out of range", [](host::ModelData& m) { m.node_children[1] = 99; }},
        {"one child only", [](host::ModelData& m) { m.node_children[1] = -1; }},
        {"leaf character out of range", [](host::ModelData& m) { m.node_characters.back() = 6; }},
        {"NaN in W", [](host::ModelData& m) { m.character_distances[7] = kNaN; }},
        {"negative W", [](host::ModelData& m) { m.character_distances[7] = -0.5f; }},
        {"zero period", [](host::ModelData& m) { m.string_period_us = 0; }},
        {"rep character out of range", [](host::ModelData& m) { m.representative_chars[0] = 6; }},
        {"empty rep", [](host::ModelData& m) { m.representative_offsets[1] = 0; }},
        {"rep label out of range", [](host::ModelData& m) { m.representative_labels[0] = 4; }},
        {"no labels", [](host::ModelData& m) { m.label_names.clear(); }},
        {"zero window", [](host::ModelData& m) { m.window_chars = 0; }},
        {"zero step", [](host::ModelData& m) { m.step_chars = 0; }},
        {"k too large", [](host::ModelData& m) { m.neighbours = 5; }},
        {"k zero", [](host::ModelData& m) { m.neighbours = 0; }},
        {"NaN threshold", [](host::ModelData& m) { m.unknown_distance = kNaN; }},
        {"bad variant", [](host::ModelData& m) { m.variant = static_cast<MatchVariant>(7); }},
    };
    for (const auto& entry : corruptions) {
        const char* name = entry.first;
        const auto& corrupt = entry.second;
        CAPTURE(name);
        host::ToyWorld world = host::make_toy_world();
        corrupt(world.model);
        const ModelView view = world.model.view();
        CHECK(validate_model(view) == Status::invalid_model);
        Annotator<Cap> annotator;
        CHECK(annotator.init(view) == Status::invalid_model);
        const float frame[15] = {};
        CHECK(annotator.push_frame(0, frame).status == Status::not_initialized);
        CHECK(annotator.label() == unknown_label);
    }
}

TEST_CASE("a model larger than the capacity is refused") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    CHECK(Annotator<Capacity<FewJoints>>{}.init(view) == Status::model_exceeds_capacity);
    CHECK(Annotator<Capacity<FewComponents>>{}.init(view) == Status::model_exceeds_capacity);
    CHECK(Annotator<Capacity<FewRepresentatives>>{}.init(view) == Status::model_exceeds_capacity);
    CHECK(Annotator<Capacity<FewRepresentativeChars>>{}.init(view) == Status::model_exceeds_capacity);
    CHECK(Annotator<Capacity<FewWindows>>{}.init(view) == Status::model_exceeds_capacity);
    CHECK(Annotator<Capacity<EnoughWindows>>{}.init(view) == Status::ok);
}

TEST_CASE("the annotator refuses a maximum gap shorter than the string period") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    Annotator<Cap> annotator;
    AnnotatorConfig config;
    config.max_gap_us = view.string_period_us - 1;
    CHECK(annotator.init(view, config) == Status::invalid_argument);
}
