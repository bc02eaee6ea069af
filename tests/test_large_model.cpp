// A model far larger than the old fixed host capacity (512 representatives,
// 32,768 representative characters): trains, evaluates, streams, and goes
// through a blob, with state sized by the model.
#include <doctest/doctest.h>

#include <random>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/blob.hpp"
#include "eval/clip_eval.hpp"
#include "io/stream.hpp"
#include "model/blob.hpp"
#include "run/state.hpp"
#include "run/stream_labels.hpp"
#include "toy/toy.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;

// Training 580 clips takes 9 s optimised and far longer unoptimised under the
// sanitizers, so this test runs in the Release suite only; the blob fuzzer and
// the other tests cover the same code paths under the sanitizers.
TEST_CASE("a 58-class model of over 500 representatives trains, evaluates and streams" *
          doctest::skip(ACTIONSTRING_SANITIZED != 0)) {
    // 58 actions: distinct random walks over the toy world's key-poses, each
    // performed 10 times (as many subjects).
    host::ToyWorld world = host::make_toy_world();
    world.actions.clear();
    std::mt19937 rng(58);
    std::uniform_int_distribution<int> pose(1, 5);
    while (world.actions.size() < 58) {
        std::vector<int> keys{0};
        for (int k = 0; k < 5; ++k) {
            int next = pose(rng);
            while (next == keys.back()) next = pose(rng);
            keys.push_back(next);
        }
        keys.push_back(0);
        bool seen = false;
        for (const auto& a : world.actions) seen = seen || a.key_poses == keys;
        if (!seen) world.actions.push_back({"action_" + std::to_string(world.actions.size()), keys, 0.35});
    }
    const std::vector<host::LabelledClip> clips = host::toy_clips(world, 10, 7);
    host::TrainingOptions options;
    options.components = 0;
    options.pca_dim = 8;
    options.string_rate_hz = 30.0;  // long strings: many representative characters
    options.keep_singletons = true;
    options.sigma = 0.01;  // every performance its own representative
    host::TrainingReport report;
    const host::ModelData model = host::train_model(clips, options, &report);
    const ModelView view = model.view();
    CHECK(view.label_count == 58);
    CHECK(view.representative_count > 512);
    CHECK(view.total_representative_chars() > 32768);
    MESSAGE(view.representative_count << " representatives of " << view.total_representative_chars()
                                      << " characters in all");

    // Clips, through the host tools (every clip is its own representative here).
    const host::ClipResults results = host::evaluate_model(view, clips);
    CHECK(results.clip_accuracy > 0.9);

    // A stream of every action back to back, through an annotator sized for this model.
    std::vector<host::StreamSegment> segments;
    for (std::size_t a = 0; a < 58; ++a) segments.push_back({&clips[a].clip, clips[a].label, 0.0});
    const host::ConcatenatedStream stream = host::concatenate_stream(segments);
    AnnotatorConfig config = annotator_config(view);
    config.window_rule = true;
    host::Stateful<Annotator> annotator;
    REQUIRE(annotator.init(view, config) == Status::ok);
    MESSAGE("annotator state: " << annotator.storage_bytes() << " bytes");
    std::size_t live = 0;
    for (std::size_t f = 0; f < stream.frame_count(); ++f) {
        annotator->push_frame(stream.times_us[f], stream.frame(f));
        live += annotator->live_label() != unknown_label;
    }
    CHECK(live > stream.frame_count() / 2);

    // The same model as a blob, read in place, labels the same.
    const std::string bytes = host::write_blob(model);
    MESSAGE("blob: " << bytes.size() << " bytes; annotator storage with the segmenter alone: "
                     << Annotator::required_bytes(view, annotator_config(view)) << " bytes");
    struct Block {
        alignas(blob_alignment) unsigned char bytes[blob_alignment];
    };
    std::vector<Block> blob(bytes.size() / blob_alignment + 1);
    std::copy(bytes.begin(), bytes.end(), blob.front().bytes);
    ModelView blob_view;
    REQUIRE(model_from_blob(blob.front().bytes, bytes.size(), blob_view) == Status::ok);
    host::Stateful<Annotator> from_blob;
    REQUIRE(from_blob.init(blob_view, config) == Status::ok);
    annotator->reset();
    for (std::size_t f = 0; f < stream.frame_count(); ++f) {
        annotator->push_frame(stream.times_us[f], stream.frame(f));
        from_blob->push_frame(stream.times_us[f], stream.frame(f));
        REQUIRE(annotator->live_label() == from_blob->live_label());
        REQUIRE(annotator->label() == from_blob->label());
    }
}
