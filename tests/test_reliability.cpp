// Regression tests for the defects a hostile probe found (issue "Reliability"):
// each failed before its fix. Defects with a natural home elsewhere are tested
// there: skeleton mismatch (test_skeleton.cpp), time (test_sampler.cpp),
// files and units (test_readers.cpp), the C API (c_api/test_c_api.c).
#include <doctest/doctest.h>

#include <memory>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/segmenter.hpp"
#include "common/cpp_literals.hpp"
#include "common/json.hpp"
#include "io/stream.hpp"
#include "model/artifact.hpp"
#include "model/header.hpp"
#include "run/encode.hpp"
#include "run/state.hpp"
#include "run/stream_labels.hpp"
#include "toy/toy.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

// The artifact text of a model whose tables were changed after training; the
// checksum is valid, so only validation can refuse it.
std::string artifact_of(const ModelData& model) { return serialize_model(model); }

}  // namespace

TEST_CASE("defect 2: an annotator cannot be set up to emit unbounded characters in one frame") {
    ToyWorld world = make_toy_world();
    ModelView view = world.model.view();
    Stateful<Annotator> annotator;
    AnnotatorConfig config;
    config.max_gap_us = 100000000000;  // 1e5 s: one frame across it took 3.2 s
    CHECK(annotator.init(view, config) == Status::invalid_argument);
    config.max_gap_us = 1000000;
    CHECK(annotator.init(view, config) == Status::ok);
    // A model whose string period is 1 µs (valid checksum) is refused, not padded to gigabytes.
    world.model.string_period_us = 1;
    CHECK_THROWS_WITH_AS(parse_model("fast.model", artifact_of(world.model)), doctest::Contains("string_period_us"),
                         ReadError);
}

TEST_CASE("defect 2: a gap in a file restarts its string instead of padding it") {
    // Before: the host padded every gap with repeated ticks, so a UTKinect file whose
    // frame ids jumped by 2e9 made train die of bad_alloc, and a 55-minute gap
    // trained silently at 755 MB.
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    LabelledClip clip = toy_clips(world, 1, 9).front();
    const std::size_t plain = clip_string(view, clip.clip).size();
    std::vector<float> poses;
    sample_poses(view, clip.clip, 30.0, poses);
    const std::size_t plain_poses = poses.size();
    const std::size_t half = clip.clip.frame_count() / 2;
    for (std::size_t f = half; f < clip.clip.frame_count(); ++f) clip.clip.times[f] += 6.7e7;  // 2e9 ids at 30 Hz
    const std::size_t gapped = clip_string(view, clip.clip).size();
    CHECK(gapped <= plain + 1);  // one tick more at most: the restart's tick 0
    CHECK(gapped + 2 >= plain);
    poses.clear();
    sample_poses(view, clip.clip, 30.0, poses);
    CHECK(poses.size() <= plain_poses + 4 * view.pose_dim());
}

TEST_CASE("defect 7: a settle delay that would overflow is refused, not undefined behaviour") {
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    Stateful<ActionSegmenter> segmenter;
    SegmenterConfig config;
    config.settle_delay_us = std::numeric_limits<std::int64_t>::max();
    CHECK(segmenter.init(view, config) == Status::invalid_argument);
    CHECK(ActionSegmenter::required_bytes(view, config) == unsatisfiable_bytes);
    config.settle_delay_us = max_settle_delay_us + 1;
    CHECK(segmenter.init(view, config) == Status::invalid_argument);
}

TEST_CASE("defect 8: models that load but misbehave are refused at load, naming the field") {
    SUBCASE("65,537 representatives do not narrow to 1") {
        ToyWorld world = make_toy_world();
        const std::vector<Character> string(1, 0);
        while (world.model.representative_labels.size() < 65537) world.model.add_representative(string, 0);
        CHECK_THROWS_WITH_AS(parse_model("many.model", artifact_of(world.model)),
                             doctest::Contains("representative_labels"), ReadError);
    }
    SUBCASE("a log-weight of 3e38 cannot pin every label to one class") {
        ToyWorld world = make_toy_world();
        world.model.gmm_log_weights[0] = 3e38f;
        CHECK_THROWS_WITH_AS(parse_model("pinned.model", artifact_of(world.model)),
                             doctest::Contains("gmm_log_weights"), ReadError);
    }
    SUBCASE("a log-normaliser of 3e38 neither") {
        ToyWorld world = make_toy_world();
        world.model.gmm_log_normalizers[1] = 3e38f;
        CHECK_THROWS_WITH_AS(parse_model("pinned.model", artifact_of(world.model)),
                             doctest::Contains("gmm_log_normalizers"), ReadError);
    }
    SUBCASE("codegen refuses every model the runtime's init() refuses") {
        const std::vector<std::pair<const char*, void (*)(ModelData&)>> mutations{
            {"factors beyond bounds", [](ModelData& m) { for (float& f : m.gmm_factors) f *= 1e6f; }},
            {"a positive log-weight", [](ModelData& m) { m.gmm_log_weights[0] = 1.0f; }},
            {"a 999 us string period", [](ModelData& m) { m.string_period_us = 999; }},
            {"a negative W", [](ModelData& m) { m.character_distances[1] = -1.0f; }},
            {"a centroid of 1e7", [](ModelData& m) { m.node_centroids[0] = 1e7f; }},
            {"a hip beyond the skeleton", [](ModelData& m) { m.left_hip_joint = 9; }},
            {"k above R", [](ModelData& m) { m.neighbours = 99; }},
        };
        for (const auto& mutation : mutations) {
            CAPTURE(mutation.first);
            ToyWorld world = make_toy_world();
            mutation.second(world.model);
            Stateful<Annotator> annotator;
            const ModelView view = world.model.view();
            CHECK(annotator.init(view, annotator_config(view)) != Status::ok);
            CHECK_THROWS_AS(generate_header(world.model, "0", "toy", "toy.model"), ReadError);
            CHECK_THROWS_AS(parse_model("bad.model", artifact_of(world.model)), ReadError);
        }
    }
}

TEST_CASE("defect 9: nothing a name holds can inject code into a generated header") {
    ToyWorld world = make_toy_world();
    const std::string checksum = artifact_checksum(artifact_of(world.model));
    const std::string header = generate_header(world.model, checksum, "toy", "evil\n#error injected\n.model");
    CHECK(header.find("\n#error") == std::string::npos);
    CHECK(header.find("evil\\x0a#error injected\\x0a.model") != std::string::npos);
    for (const char* ns : {"a:b", "int", "a::", "::a", "a b", "1a", "", "a::namespace"})
        CHECK_THROWS_AS(generate_header(world.model, checksum, ns, "toy.model"), std::invalid_argument);
    for (const char* ns : {"a", "a::b", "_x1::y_2"}) CHECK_NOTHROW(generate_header(world.model, checksum, ns, "m"));

    // The replay stream: the list name goes into the banner the same way.
    const std::vector<LabelledClip> clips = toy_clips(world, 1, 3);
    const std::vector<StreamSegment> segments{{&clips[0].clip, clips[0].label, 0.0}};
    const std::string stream = generate_stream_header(segments, "s", "stream-table --clips <a\n#error b>");
    CHECK(stream.find("\n#error") == std::string::npos);
    CHECK_THROWS_AS(generate_stream_header(segments, "in valid", "x"), std::invalid_argument);
}

TEST_CASE("defect 10: messages say what was expected; JSON stays valid UTF-8") {
    // --settle 4.1 (advertised up to 60) failed with "settings do not fit the host annotator".
    ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    AnnotatorConfig config;
    config.segmenter.settle_delay_us = 4100000;
    const std::vector<float> frame(3 * 5, 0.0f);
    CHECK_NOTHROW(label_stream(view, config, {0.0}, frame.data(), 5));
    config.segmenter.settle_delay_us = 600000000;  // 10 minutes: the state grows with it, and holds it
    CHECK_NOTHROW(label_stream(view, config, {0.0}, frame.data(), 5));
    config.segmenter.settle_delay_us = 600000001;  // beyond the runtime's limit: refused, saying so
    CHECK_THROWS_WITH_AS(label_stream(view, config, {0.0}, frame.data(), 5), doctest::Contains("is outside 0 to 600"),
                         std::invalid_argument);

    // Left hip equal to right hip was reported as "no usable frames".
    std::vector<LabelledClip> clips = toy_clips(world, 2, 5);
    for (LabelledClip& c : clips) c.clip.roles.right_hip = c.clip.roles.left_hip;
    CHECK_THROWS_WITH_AS(train_model(clips, TrainingOptions{}), doctest::Contains("the same joint"),
                         std::invalid_argument);

    // A Latin-1 label made eval --json write invalid UTF-8.
    CHECK(json_string("caf\xe9") == "\"caf\xc3\xa9\"");              // Latin-1 é, as UTF-8
    CHECK(json_string("caf\xc3\xa9") == "\"caf\xc3\xa9\"");          // already UTF-8: unchanged
    CHECK(json_string("\xed\xa0\x80") == "\"\xc3\xad\xc2\xa0\xc2\x80\"");  // a surrogate is not UTF-8
    CHECK(json_string("a\"b\n") == "\"a\\\"b\\u000a\"");
    JsonWriter out;
    out.begin_object().field("nan", std::numeric_limits<double>::quiet_NaN()).field("x", 0.5).end_object();
    CHECK(out.str() == "{\"nan\": null, \"x\": 0.5}\n");
}
