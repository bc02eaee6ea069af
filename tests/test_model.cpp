// Model validation: every corrupted table is refused before it reaches the per-frame code.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>

#include "actionstring/annotator.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"

using namespace actionstring;

namespace {
const float kNaN = std::numeric_limits<float>::quiet_NaN();
}  // namespace

TEST_CASE("the toy model is valid") {
    host::ToyWorld world = host::make_toy_world();
    CHECK(validate_model(world.model.view()) == Status::ok);
}

namespace {
// Valid exemplars for the toy model: one centre per entry of `labels`
// (unknown_label: a centre of no action), at the origin.
void with_exemplars(host::ModelData& m, const std::vector<LabelId>& labels) {
    m.exemplar_labels = labels;
    m.exemplars.assign(labels.size() * m.feature_dim, 0.0f);
    m.exemplar_weight = 1.0f;
    m.exemplar_scale = 1.0f;
}
}  // namespace

TEST_CASE("exemplars of the labels and of no action validate") {
    host::ToyWorld world = host::make_toy_world();
    with_exemplars(world.model, {0, 1, 1, unknown_label, unknown_label});
    CHECK(validate_model(world.model.view()) == Status::ok);
    CHECK(world.model.view().has_no_action_exemplars());
    with_exemplars(world.model, {0, 1});
    CHECK(validate_model(world.model.view()) == Status::ok);
    CHECK_FALSE(world.model.view().has_no_action_exemplars());
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
        {"negative vote weight", [](host::ModelData& m) { m.vote_weight = -1.0f; }},
        {"NaN online vote weight", [](host::ModelData& m) { m.segment_vote_weight = kNaN; }},
        {"online vote weight beyond 1000", [](host::ModelData& m) { m.segment_vote_weight = 2000.0f; }},
        {"NaN online exemplar weight", [](host::ModelData& m) { m.segment_exemplar_weight = kNaN; }},
        {"negative online direction weight", [](host::ModelData& m) { m.segment_direction_weight = -4.8e-7f; }},
        {"NaN online direction weight", [](host::ModelData& m) { m.segment_direction_weight = kNaN; }},
        {"online direction weight beyond 1000", [](host::ModelData& m) { m.segment_direction_weight = 1001.0f; }},
        {"shortest action over 10 minutes", [](host::ModelData& m) { m.min_action_us = 600000001u; }},
        {"votes missing", [](host::ModelData& m) { m.vote_weight = 1.0f; }},
        {"NaN vote",
         [](host::ModelData& m) {
             m.vote_weight = 1.0f;
             m.character_votes.assign(m.label_names.size() * m.character_count, -1.0f);
             m.character_votes[3] = kNaN;
         }},
        {"no-action votes flagged but missing",
         [](host::ModelData& m) {
             m.vote_weight = 1.0f;
             m.character_votes.assign(m.label_names.size() * m.character_count, -1.0f);
             m.has_no_action_votes = 1;
         }},
        {"NaN no-action vote",
         [](host::ModelData& m) {
             m.vote_weight = 1.0f;
             m.character_votes.assign(m.label_names.size() * m.character_count, -1.0f);
             m.has_no_action_votes = 1;
             m.no_action_votes.assign(m.character_count, -2.0f);
             m.no_action_votes[1] = kNaN;
         }},
        {"label bounds flagged but missing", [](host::ModelData& m) { m.has_label_bounds = 1; }},
        {"NaN label bound",
         [](host::ModelData& m) {
             m.has_label_bounds = 1;
             m.label_bounds.assign(m.label_names.size(), 2.0f);
             m.label_bounds[1] = kNaN;
         }},
        {"negative label bound",
         [](host::ModelData& m) {
             m.has_label_bounds = 1;
             m.label_bounds.assign(m.label_names.size(), -1.0f);
         }},
        {"exemplar label out of range",
         [](host::ModelData& m) {
             with_exemplars(m, {0, 9});
         }},
        {"a label's exemplar after no action's",
         [](host::ModelData& m) {
             with_exemplars(m, {unknown_label, 0});
         }},
        {"NaN exemplar",
         [](host::ModelData& m) {
             with_exemplars(m, {0, 1});
             m.exemplars[1] = kNaN;
         }},
        {"exemplar weight without a scale",
         [](host::ModelData& m) {
             with_exemplars(m, {0, 1});
             m.exemplar_scale = 0.0f;
         }},
        {"vote not a log-probability",
         [](host::ModelData& m) {
             m.vote_weight = 1.0f;
             m.character_votes.assign(m.label_names.size() * m.character_count, -1.0f);
             m.character_votes.back() = 0.5f;
         }},
    };
    for (const auto& entry : corruptions) {
        const char* name = entry.first;
        const auto& corrupt = entry.second;
        CAPTURE(name);
        host::ToyWorld world = host::make_toy_world();
        corrupt(world.model);
        const ModelView view = world.model.view();
        CHECK(validate_model(view) == Status::invalid_model);
        host::Stateful<Annotator> annotator;
        CHECK(annotator.init(view, annotator_config(view)) == Status::invalid_model);
        const float frame[15] = {};
        CHECK(annotator->push_frame(0, frame).status == Status::not_initialized);
        CHECK(annotator->label() == unknown_label);
        // A broken model is reported as such, not as a size, whatever the storage.
        alignas(state_alignment) static unsigned char small[64];
        CHECK(Annotator{}.init(view, annotator_config(view), small, sizeof small) == Status::invalid_model);
    }
}

TEST_CASE("a model that validates runs with its own online settings") {
    // The model's online fields and the settings init() takes are checked in
    // two places (validation and SegmenterConfig's check); a value only one of
    // them refuses gives a model that validates yet cannot start with its own
    // settings, as the blob fuzzer once found with a negative direction weight.
    using Field = float host::ModelData::*;
    const Field floats[] = {&host::ModelData::segment_penalty,       &host::ModelData::stay_penalty,
                            &host::ModelData::skip_penalty,          &host::ModelData::unknown_cost,
                            &host::ModelData::segment_vote_weight,   &host::ModelData::segment_exemplar_weight,
                            &host::ModelData::segment_direction_weight};
    const float inf = std::numeric_limits<float>::infinity();
    const float float_values[] = {-inf, -1.0f, -4.8e-7f, 0.0f, 0.5f, 1000.0f, 1000.5f, 1.0e6f, 2.0e6f, inf, kNaN};
    using Count = std::uint32_t host::ModelData::*;
    const Count counts[] = {&host::ModelData::settle_delay_us, &host::ModelData::settle_stable_us,
                            &host::ModelData::min_action_us, &host::ModelData::label_lead_us};
    const std::uint32_t count_values[] = {0u, 1u, 600000000u, 600000001u, 0xFFFFFFFFu};
    std::size_t accepted = 0, refused = 0;
    const auto check = [&](const host::ModelData& m) {
        const ModelView view = m.view();
        if (validate_model(view) != Status::ok) {
            ++refused;
            return;
        }
        ++accepted;
        CHECK(ActionSegmenter::check(view, segmenter_config(view)) == Status::ok);
        host::Stateful<Annotator> annotator;
        CHECK(annotator.init(view, annotator_config(view)) == Status::ok);
    };
    const auto sweep = [&](const auto& fields, const auto& values) {
        for (const auto field : fields)
            for (const auto value : values) {
                host::ToyWorld world = host::make_toy_world();
                world.model.*field = value;
                CAPTURE(value);
                check(world.model);
            }
    };
    sweep(floats, float_values);
    sweep(counts, count_values);
    // Both outcomes occur, so neither half of the check is vacuous.
    CHECK(accepted > 20);
    CHECK(refused > 20);
}

TEST_CASE("the annotator works in exactly the storage the model needs") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    AnnotatorConfig config = annotator_config(view);
    const std::size_t segmenter_only = Annotator::required_bytes(view, config);
    config.window_rule = true;
    const std::size_t both_rules = Annotator::required_bytes(view, config);
    CHECK(segmenter_only > 0);
    CHECK(both_rules > segmenter_only);  // the window matcher's state is paid for only when asked
    CHECK(both_rules == Annotator::required_bytes(view, config));  // a pure function of model and settings
    CHECK(both_rules % state_alignment == 0);

    std::vector<unsigned char> bytes(both_rules + 2 * state_alignment);
    unsigned char* aligned = bytes.data();
    while (reinterpret_cast<std::uintptr_t>(aligned) % state_alignment != 0) ++aligned;
    Annotator annotator;
    CHECK(annotator.init(view, config, aligned, both_rules - 1) == Status::storage_too_small);
    CHECK(annotator.init(view, config, nullptr, both_rules) == Status::storage_too_small);
    CHECK(annotator.init(view, config, aligned + 1, both_rules) == Status::storage_too_small);
    CHECK(!annotator.initialized());
    REQUIRE(annotator.init(view, config, aligned, both_rules) == Status::ok);
    // Nothing is written outside the block the annotator was given.
    std::fill(aligned + both_rules, bytes.data() + bytes.size(), static_cast<unsigned char>(0xA5));
    for (const auto& frame : host::toy_stream(world, {0, 1, 2, 3}, host::ToyStreamOptions{}))
        annotator.push_frame(frame.time_us, frame.positions.data());
    CHECK(annotator.label() != unknown_label);
    for (const unsigned char* p = aligned + both_rules; p < bytes.data() + bytes.size(); ++p) REQUIRE(*p == 0xA5);
    // A longer settle delay needs a longer ring.
    config.segmenter.settle_delay_us *= 8;
    CHECK(Annotator::required_bytes(view, config) > both_rules);
    CHECK(annotator.init(view, config, aligned, both_rules) == Status::storage_too_small);
}

TEST_CASE("the annotator refuses a maximum gap shorter than the string period") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    host::Stateful<Annotator> annotator;
    AnnotatorConfig config;
    config.max_gap_us = view.string_period_us - 1;
    CHECK(annotator.init(view, config) == Status::invalid_argument);
}

TEST_CASE("packed names are checked: terminated, non-empty, no NUL inside, offsets from 0") {
    host::ToyWorld world = host::make_toy_world();
    ModelView view = world.model.view();
    REQUIRE(view.label_count == 4);
    static constexpr char good[] = "a\0b\0c\0d";
    static constexpr std::uint32_t good_offsets[5] = {0, 2, 4, 6, 8};
    view.label_names = NameTable{good, good_offsets};
    CHECK(validate_model(view) == Status::ok);
    CHECK(std::string(view.label_names[3]) == "d");
    static constexpr char unterminated[] = "a\0b\0c\0dd";
    static constexpr std::uint32_t unterminated_offsets[5] = {0, 2, 4, 6, 8};
    static constexpr std::uint32_t empty_name[5] = {0, 2, 4, 6, 6};
    static constexpr std::uint32_t late_start[5] = {2, 2, 4, 6, 8};
    static constexpr char inner_nul[] = "a\0\0\0c\0d";
    static constexpr std::uint32_t inner_offsets[5] = {0, 2, 2, 6, 8};
    const char* problem = "";
    for (const NameTable names :
         {NameTable{unterminated, unterminated_offsets}, NameTable{good, empty_name}, NameTable{good, late_start},
          NameTable{inner_nul, inner_offsets}, NameTable{nullptr, good_offsets}, NameTable{good, nullptr}}) {
        view.label_names = names;
        CHECK(validate_model(view, &problem) == Status::invalid_model);
        CHECK(std::string(problem).rfind("label_names", 0) == 0);
    }
}
