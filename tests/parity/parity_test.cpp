// The runtime compiled against a generated header and the same runtime on the
// host-loaded artifact must agree bit for bit: characters, window distances,
// labels and confidences, frame by frame.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <cstring>
#include <memory>

#include "actionstring/annotator.hpp"
#include "actionstring/blob.hpp"
#include "model/artifact.hpp"
#include "model/blob.hpp"
#include "model/header.hpp"
#include "io/stream.hpp"
#include "io/text.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"
#include "fixture_model.hpp"
#include "fixture_pca_model.hpp"

using namespace actionstring;

namespace {

// Both rules, so window distances are compared too.
AnnotatorConfig every_rule(const ModelView& model) {
    AnnotatorConfig config = annotator_config(model);
    config.window_rule = true;
    return config;
}

// Feeds one frame to both annotators and requires identical results; counts completed windows.
void push_both(Annotator& generated, Annotator& host_side, const ModelView& view, std::int64_t time_us,
               const float* positions, std::size_t& windows, std::size_t& characters, Annotator* blob_side = nullptr) {
    const FrameResult a = generated.push_frame(time_us, positions);
    const FrameResult b = host_side.push_frame(time_us, positions);
    if (blob_side != nullptr) {
        // The blob read in place, a third copy of the same model.
        const FrameResult c = blob_side->push_frame(time_us, positions);
        REQUIRE(c.status == a.status);
        REQUIRE(c.characters_settled == a.characters_settled);
        REQUIRE(blob_side->last_character() == generated.last_character());
        REQUIRE(blob_side->label() == generated.label());
        REQUIRE(blob_side->live_label() == generated.live_label());
        if (c.characters_settled > 0) REQUIRE(blob_side->settled_label() == generated.settled_label());
        const float cc = blob_side->confidence(), ca = generated.confidence();
        REQUIRE(std::memcmp(&cc, &ca, sizeof cc) == 0);
    }
    REQUIRE(a.status == b.status);
    REQUIRE(a.characters == b.characters);
    REQUIRE(a.windows_completed == b.windows_completed);
    REQUIRE(generated.last_character() == host_side.last_character());
    REQUIRE(generated.label() == host_side.label());
    REQUIRE(generated.live_label() == host_side.live_label());
    REQUIRE(a.characters_settled == b.characters_settled);
    if (a.characters_settled > 0) REQUIRE(generated.settled_label() == host_side.settled_label());
    const float ca = generated.confidence(), cb = host_side.confidence();
    REQUIRE(std::memcmp(&ca, &cb, sizeof ca) == 0);
    if (a.windows_completed > 0) {
        REQUIRE(std::memcmp(generated.last_window_distances(), host_side.last_window_distances(),
                            sizeof(float) * view.representative_count) == 0);
        ++windows;
    }
    characters += a.characters;
}

}  // namespace

namespace {

// Streams a jittery toy performance with dropped frames through the generated
// header's annotator (in a static buffer of the header's exact size) and the
// loaded artifact's (storage allocated for it), requiring identical results.
template <std::size_t GeneratedBytes>
void check_parity(const ModelView& generated_model, const char* checksum, const char* artifact_path) {
    host::ModelData loaded = host::load_model(artifact_path);
    const ModelView view = loaded.view();
    CHECK(std::strcmp(checksum + 8, host::artifact_checksum(host::read_file(artifact_path)).c_str()) == 0);
    auto storage = std::make_unique<StateBuffer<GeneratedBytes>>();
    auto generated = std::make_unique<Annotator>();
    host::Stateful<Annotator> host_side;
    REQUIRE(generated->init(generated_model, every_rule(generated_model), storage->data(), storage->size()) ==
            Status::ok);
    REQUIRE(host_side.init(view, every_rule(view)) == Status::ok);
    CHECK(host_side.storage_bytes() == GeneratedBytes);
    // The same artifact as a blob, read in place.
    const std::string bytes = host::write_blob(loaded);
    struct Block {
        alignas(blob_alignment) unsigned char bytes[blob_alignment];
    };
    std::vector<Block> blob(bytes.size() / blob_alignment + 1);
    std::memcpy(blob.front().bytes, bytes.data(), bytes.size());
    ModelView blob_view;
    REQUIRE(model_from_blob(blob.front().bytes, bytes.size(), blob_view) == Status::ok);
    host::Stateful<Annotator> blob_side;
    REQUIRE(blob_side.init(blob_view, every_rule(blob_view)) == Status::ok);

    host::ToyWorld world = host::make_toy_world();
    std::vector<int> sequence;
    for (int i = 0; i < 24; ++i) sequence.push_back((i * 7) % 4);
    host::ToyStreamOptions stream;
    stream.seed = 4242;
    stream.frame_time_jitter = 0.3;
    stream.drop_probability = 0.05;
    std::size_t windows = 0, characters = 0;
    for (const auto& frame : host::toy_stream(world, sequence, stream))
        push_both(*generated, *host_side, view, frame.time_us, frame.positions.data(), windows, characters,
                  &*blob_side);
    CHECK(windows > 100);
    CHECK(characters > 500);
}

}  // namespace

TEST_CASE("generated header and loaded artifact agree bit for bit") {
    check_parity<fixture::kAnnotatorWithWindowsBytes>(fixture::kModel, fixture::kModelChecksum,
                                                      ACTIONSTRING_FIXTURE_MODEL);
}

TEST_CASE("the same without a GMM: the tree descends on projected poses") {
    CHECK(fixture_pca::kModel.component_count == 0);
    check_parity<fixture_pca::kAnnotatorWithWindowsBytes>(fixture_pca::kModel, fixture_pca::kModelChecksum,
                                                          ACTIONSTRING_FIXTURE_PCA_MODEL);
}

#if defined(ACTIONSTRING_WITH_EXAMPLE_MODEL)
#include <cstdlib>

#include "io/clip_list.hpp"
#include "io/formats.hpp"
#include "hdm05_model.hpp"

// Real clips through the committed example header and through the artifact the
// regeneration test just trained (ACTIONSTRING_EXAMPLE_ARTIFACT); skipped when absent.
TEST_CASE("the committed HDM05 header and its artifact agree bit for bit on real clips") {
    const char* artifact = std::getenv("ACTIONSTRING_EXAMPLE_ARTIFACT");
    const char* list = std::getenv("ACTIONSTRING_EXAMPLE_CLIPS");
    if (artifact == nullptr || list == nullptr || std::getenv("ACTIONSTRING_EXAMPLE_SKIP") != nullptr) {
        MESSAGE("SKIPPED: no example artifact or clip list (HDM05 data absent)");
        return;
    }
    host::ModelData loaded = host::load_model(artifact);
    const ModelView view = loaded.view();
    REQUIRE(std::strcmp(actionstring_hdm05::kModelChecksum + 8,
                        host::artifact_checksum(host::read_file(artifact)).c_str()) == 0);
    auto storage = std::make_unique<StateBuffer<actionstring_hdm05::kAnnotatorWithWindowsBytes>>();
    auto generated = std::make_unique<Annotator>();
    host::Stateful<Annotator> host_side;
    REQUIRE(generated->init(actionstring_hdm05::kModel, every_rule(actionstring_hdm05::kModel), storage->data(),
                            storage->size()) == Status::ok);
    REQUIRE(host_side.init(view, every_rule(view)) == Status::ok);
    std::size_t windows = 0, characters = 0;
    std::int64_t offset = 0;
    for (const host::ClipListEntry& entry : host::read_clip_list(list)) {
        const host::Clip clip = host::read_clip(entry);
        for (std::size_t f = 0; f < clip.frame_count(); ++f)
            push_both(*generated, *host_side, view, offset + static_cast<std::int64_t>(clip.times[f] * 1e6),
                      clip.frame(f), windows, characters);
        offset += static_cast<std::int64_t>(clip.duration() * 1e6) + 8333;
    }
    CHECK(windows > 100);
}
#endif
