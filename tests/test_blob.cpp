// The model blob: written from the schema, read in place by the runtime,
// bit-identical in use, and refused with a reason when damaged or hostile.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/blob.hpp"
#include "model/artifact.hpp"
#include "io/text.hpp"
#include "model/blob.hpp"
#include "run/state.hpp"
#include "test_support.hpp"
#include "toy/toy.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;

namespace {

// A blob's bytes at an address aligned for the runtime.
struct AlignedBlob {
    explicit AlignedBlob(const std::string& bytes) : blocks(bytes.size() / 16 + 1), size(bytes.size()) {
        std::memcpy(data(), bytes.data(), bytes.size());
    }
    unsigned char* data() { return blocks.front().bytes; }
    struct Block {
        alignas(16) unsigned char bytes[16];
    };
    std::vector<Block> blocks;
    std::size_t size;
};

std::uint64_t read_u64(const std::string& b, std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
    return v;
}
void write_u64(std::string& b, std::size_t at, std::uint64_t v) {
    for (std::size_t i = 0; i < 8; ++i) b[at + i] = static_cast<char>((v >> (8 * i)) & 0xFFu);
}
// A damaged blob whose checksum is made valid again: only the structural checks can refuse it.
void rechecksum(std::string& b) {
    write_u64(b, 24, detail::blob_checksum(reinterpret_cast<const unsigned char*>(b.data()), b.size()));
}

// Where the directory entry of the n-th schema field is.
std::size_t entry(std::size_t n) { return 64 + 32 * n; }
std::size_t field_index(const char* wanted) {
    std::size_t n = 0, found = 0;
    bool seen = false;
    auto visit = [&](const char* name) {
        if (!seen && std::strcmp(name, wanted) == 0) found = n, seen = true;
        ++n;
    };
#define VISIT_SCALAR(T, FIELD, INITIAL, LOW, HIGH) visit(#FIELD);
#define VISIT_COUNT(T, FIELD, TABLE) visit(#FIELD);
#define VISIT_TABLE(T, FIELD, SIZE, LOW, HIGH) visit(#FIELD);
#define VISIT_NAMES(FIELD, COUNT) visit(#FIELD);
    ACTIONSTRING_MODEL_FIELDS(VISIT_SCALAR, VISIT_COUNT, VISIT_TABLE, VISIT_NAMES)
#undef VISIT_SCALAR
#undef VISIT_COUNT
#undef VISIT_TABLE
#undef VISIT_NAMES
    REQUIRE(seen);
    return found;
}

Status read(const std::string& bytes, ModelView& view, const char** problem) {
    static AlignedBlob* keep = nullptr;  // the view points into it until the next call
    delete keep;
    keep = new AlignedBlob(bytes);
    return model_from_blob(keep->data(), keep->size, view, problem);
}

}  // namespace

TEST_CASE("a blob round-trips every field, deterministically") {
    for (const Covariance covariance : {Covariance::full, Covariance::diagonal}) {
        host::ToyOptions options;
        options.covariance = covariance;
        host::ToyWorld world = host::make_toy_world(options);
        const std::string blob = host::write_blob(world.model);
        CHECK(blob == host::write_blob(world.model));
        CHECK(host::looks_like_blob(blob));
        CHECK(blob.size() % 16 == 0);
        const host::ModelData back = host::read_blob("toy.blob", blob);
        CHECK(host::serialize_model(back) == host::serialize_model(world.model));
    }
    // A model with bone lengths, motion and no GMM too.
    host::ToyWorld world = host::make_toy_world();
    host::TrainingOptions options;
    options.components = 0;
    options.pca_dim = 8;
    options.velocity_weight = 1.0;
    options.velocity_span_s = 0.3;
    options.scale_mode = ScaleMode::bone_lengths;
    // And exemplars of the feature's first 5 coordinates.
    options.exemplars = 4;
    options.exemplar_weight = 1.0;
    options.exemplar_dims = 5;
    const host::ModelData model = host::train_model(host::toy_clips(world, 2, 6), options);
    REQUIRE(model.exemplar_dim == 5);
    const host::ModelData back = host::read_blob("motion.blob", host::write_blob(model));
    CHECK(host::serialize_model(back) == host::serialize_model(model));
}

TEST_CASE("the runtime reads a blob in place and labels bit for bit as the host model does") {
    host::ToyWorld world = host::make_toy_world();
    const std::string bytes = host::write_blob(world.model);
    AlignedBlob blob(bytes);
    ModelView view;
    REQUIRE(model_from_blob(blob.data(), blob.size, view) == Status::ok);
    // In place: the tables are inside the blob, not copies.
    const auto* begin = reinterpret_cast<const char*>(blob.data());
    const auto* table = reinterpret_cast<const char*>(view.character_distances);
    CHECK(table >= begin);
    CHECK(table < begin + blob.size);
    CHECK(std::string(view.label_names[0]) == world.model.label_names[0]);

    const ModelView host_view = world.model.view();
    host::Stateful<Annotator> from_blob, from_host;
    REQUIRE(from_blob.init(view, test::every_rule(view)) == Status::ok);
    REQUIRE(from_host.init(host_view, test::every_rule(host_view)) == Status::ok);
    CHECK(from_blob.storage_bytes() == from_host.storage_bytes());
    host::ToyStreamOptions stream;
    stream.frame_time_jitter = 0.3;
    stream.drop_probability = 0.05;
    std::size_t windows = 0;
    for (const auto& frame : host::toy_stream(world, {0, 1, 2, 3, 2, 1, 0}, stream)) {
        const FrameResult a = from_blob->push_frame(frame.time_us, frame.positions.data());
        const FrameResult b = from_host->push_frame(frame.time_us, frame.positions.data());
        REQUIRE(a.status == b.status);
        REQUIRE(from_blob->last_character() == from_host->last_character());
        REQUIRE(from_blob->live_label() == from_host->live_label());
        REQUIRE(from_blob->label() == from_host->label());
        const float ca = from_blob->confidence(), cb = from_host->confidence();
        REQUIRE(std::memcmp(&ca, &cb, sizeof ca) == 0);
        windows += a.windows_completed;
    }
    CHECK(windows > 20);
}

TEST_CASE("a damaged or hostile blob is refused with a reason, never read out of bounds") {
    host::ToyWorld world = host::make_toy_world();
    const std::string good = host::write_blob(world.model);
    ModelView view;
    const char* problem = "";

    // Every truncation.
    for (std::size_t size = 0; size < good.size(); size += (size < 256 ? 1 : 97)) {
        CAPTURE(size);
        CHECK(read(good.substr(0, size), view, &problem) == Status::invalid_model);
    }
    // Any flipped byte: the checksum catches it.
    for (std::size_t at = 0; at < good.size(); at += 13) {
        std::string bad = good;
        bad[at] = static_cast<char>(bad[at] ^ 0x40);
        CHECK(read(bad, view, &problem) == Status::invalid_model);
    }
    // Misaligned or null bytes.
    AlignedBlob aligned(good + std::string(16, '\0'));
    std::memmove(aligned.data() + 4, aligned.data(), good.size());
    CHECK(model_from_blob(aligned.data() + 4, good.size(), view, &problem) == Status::invalid_argument);
    CHECK(model_from_blob(nullptr, good.size(), view, &problem) == Status::invalid_argument);

    struct Case {
        const char* what;
        void (*damage)(std::string&);
        const char* expected;
    };
    const Case cases[] = {
        {"another version", [](std::string& b) { b[8] = static_cast<char>(blob_version + 1); }, "version"},
        {"size field larger than the bytes", [](std::string& b) { write_u64(b, 16, b.size() + 16); }, "truncated"},
        {"a table far past the end",
         [](std::string& b) { write_u64(b, entry(field_index("character_distances")) + 8, 1ull << 60); },
         "character_distances"},
        {"a table offset inside the directory",
         [](std::string& b) { write_u64(b, entry(field_index("node_centroids")) + 8, 64); }, "node_centroids"},
        {"a misaligned table",
         [](std::string& b) {
             const std::size_t e = entry(field_index("gmm_means")) + 8;
             write_u64(b, e, read_u64(b, e) + 4);
         },
         "gmm_means"},
        {"a huge element count",
         [](std::string& b) { write_u64(b, entry(field_index("representative_chars")) + 16, ~0ull / 2); },
         "representative_chars"},
        {"a count that disagrees with its table",
         [](std::string& b) { b[entry(field_index("representative_count")) + 8] += 1; }, "representative"},
        {"a scalar out of its range", [](std::string& b) { b[entry(field_index("up_axis")) + 8] = 7; }, "up_axis"},
        {"a scalar with stray high bytes", [](std::string& b) { b[entry(field_index("up_axis")) + 12] = 1; },
         "up_axis"},
        {"an entry of the wrong kind", [](std::string& b) { b[entry(field_index("joint_parents"))] = 1; },
         "joint_parents"},
        {"a NaN in W",
         [](std::string& b) {
             const std::size_t at = read_u64(b, entry(field_index("character_distances")) + 8) + 4;
             b[at] = 0, b[at + 1] = 0, b[at + 2] = static_cast<char>(0xC0), b[at + 3] = 0x7F;
         },
         "character_distances"},
        {"a name without its NUL",
         [](std::string& b) {
             const std::size_t e = entry(field_index("label_names"));
             const std::size_t text = read_u64(b, e + 8), bytes = read_u64(b, e + 16);
             b[text + bytes - 1] = 'x';
         },
         "label_names"},
        {"a name table longer than its text",
         [](std::string& b) { write_u64(b, entry(field_index("label_names")) + 16, 3); }, "label_names"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.what);
        std::string bad = good;
        c.damage(bad);
        rechecksum(bad);
        problem = "";
        CHECK(read(bad, view, &problem) == Status::invalid_model);
        CHECK(std::string(problem).find(c.expected) != std::string::npos);
        CHECK_THROWS_AS(host::read_blob("bad.blob", bad), host::ReadError);
    }
    CHECK(read(good, view, &problem) == Status::ok);
}

TEST_CASE("a saved blob loads wherever a model file is read") {
    host::ToyWorld world = host::make_toy_world();
    const std::string path = "test_blob_roundtrip.blob";
    host::write_file(path, host::write_blob(world.model));
    const host::ModelData loaded = host::load_model(path);
    CHECK(host::serialize_model(loaded) == host::serialize_model(world.model));
    std::remove(path.c_str());
}
