// Zero heap allocations per frame, proven with tripwires that are first shown to fire.
//
// Counts every malloc/calloc/realloc (glibc's allocator underneath), every
// global operator new, and every Eigen heap request (EIGEN_RUNTIME_NO_MALLOC
// with eigen_assert routed to a counter instead of abort()).
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> g_mallocs{0};
std::atomic<long> g_news{0};
std::atomic<long> g_eigen_violations{0};
}  // namespace

void note_eigen_violation() { ++g_eigen_violations; }

#define EIGEN_RUNTIME_NO_MALLOC
#define eigen_assert(condition)                   \
    do {                                          \
        if (!(condition)) note_eigen_violation(); \
    } while (false)

#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "actionstring/actionstring.hpp"
#include "run/state.hpp"
#include "toy/toy.hpp"
#include "toy_options.hpp"
#include "train/pipeline.hpp"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t size) {
    ++g_mallocs;
    return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
    ++g_mallocs;
    return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) {
    ++g_mallocs;
    return __libc_realloc(pointer, size);
}
void free(void* pointer) { __libc_free(pointer); }
}

void* operator new(std::size_t size) {
    ++g_news;
    if (void* p = __libc_malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* pointer) noexcept { __libc_free(pointer); }
void operator delete[](void* pointer) noexcept { __libc_free(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { __libc_free(pointer); }
void operator delete[](void* pointer, std::size_t) noexcept { __libc_free(pointer); }

namespace {

struct Counts {
    long mallocs, news, eigen;
};
Counts snapshot() { return {g_mallocs.load(), g_news.load(), g_eigen_violations.load()}; }

// Keeps the optimiser from removing an allocation whose result is unused.
void* volatile g_sink = nullptr;

}  // namespace

TEST_CASE("the tripwires fire") {
    Counts before = snapshot();
    {
        std::vector<int> v(100);
        g_sink = v.data();
    }
    CHECK(snapshot().news > before.news);

    before = snapshot();
    void* (*volatile allocate)(std::size_t) = &malloc;
    void* p = allocate(32);
    g_sink = p;
    free(p);
    CHECK(snapshot().mallocs == before.mallocs + 1);

    before = snapshot();
    Eigen::internal::set_is_malloc_allowed(false);
    {
        Eigen::MatrixXf heap_matrix(16, 16);
        g_sink = heap_matrix.data();
    }
    Eigen::internal::set_is_malloc_allowed(true);
    CHECK(snapshot().eigen > before.eigen);
}

TEST_CASE("streaming thousands of frames through the annotator allocates nothing") {
    for (const auto covariance : {actionstring::Covariance::full, actionstring::Covariance::diagonal})
        for (const bool spread : {false, true}) {  // spread: queued poses, a GMM in steps
            actionstring::host::ToyOptions options;
            options.covariance = covariance;
            options.neighbours = 3;
            actionstring::host::ToyWorld world = actionstring::host::make_toy_world(options);
            const actionstring::ModelView view = world.model.view();
            // Storage allocated once, before the stream, as a host tool does.
            actionstring::host::Stateful<actionstring::Annotator> annotator;
            actionstring::AnnotatorConfig config = actionstring::annotator_config(view);
            config.window_rule = true;
            config.spread_work = spread;
            REQUIRE(annotator.init(view, config) == actionstring::Status::ok);
            std::vector<int> sequence;
            for (int i = 0; i < 40; ++i) sequence.push_back(i % 4);
            actionstring::host::ToyStreamOptions stream;
            stream.frame_rate_hz = 60.0;
            stream.frame_time_jitter = 0.3;
            stream.drop_probability = 0.05;
            auto frames = actionstring::host::toy_stream(world, sequence, stream);
            frames[100].positions.assign(15, 0.0f);  // a lost-tracking frame on the way

            Eigen::internal::set_is_malloc_allowed(false);
            const Counts before = snapshot();
            std::size_t windows = 0;
            for (const auto& frame : frames) {
                windows += annotator->push_frame(frame.time_us, frame.positions.data()).windows_completed;
                g_sink = const_cast<char*>(annotator->label_name());
            }
            windows += annotator->finish_work().windows_completed;
            annotator->flush();
            const Counts after = snapshot();
            Eigen::internal::set_is_malloc_allowed(true);

            CHECK(frames.size() > 4000);
            CHECK(windows > 150);
            CHECK(after.mallocs == before.mallocs);
            CHECK(after.news == before.news);
            CHECK(after.eigen == before.eigen);
        }
}

TEST_CASE("a segmenter weighing exemplars and the window's directions allocates nothing, spread or not") {
    actionstring::host::ToyWorld world = actionstring::host::make_toy_world();
    actionstring::host::TrainingOptions options = test::toy_options();
    options.components = 0;
    options.pca_dim = 6;
    options.velocity_weight = 1.0;
    options.exemplars = 4;
    options.exemplar_weight = 1.0;
    options.direction_window_s = 1.0;
    options.online.exemplar_weight = 0.1f;
    options.online.direction_weight = 0.25f;
    const actionstring::host::ModelData model =
        actionstring::host::train_model(actionstring::host::toy_clips(world, 6, 100), options);
    const actionstring::ModelView view = model.view();
    REQUIRE(view.has_window_directions());
    for (const bool spread : {false, true}) {
        actionstring::host::Stateful<actionstring::Annotator> annotator;
        actionstring::AnnotatorConfig config = actionstring::annotator_config(view);
        config.spread_work = spread;
        REQUIRE(annotator.init(view, config) == actionstring::Status::ok);
        std::vector<int> sequence;
        for (int i = 0; i < 20; ++i) sequence.push_back(i % 4);
        auto frames = actionstring::host::toy_stream(world, sequence);
        for (std::size_t i = frames.size() / 2; i < frames.size(); ++i)  // a jump: the window starts again
            frames[i].positions[3 * 3 + 1] += 1.0f, frames[i].positions[4 * 3 + 1] += 1.0f;

        Eigen::internal::set_is_malloc_allowed(false);
        const Counts before = snapshot();
        std::size_t settled = 0;
        for (const auto& frame : frames)
            settled += annotator->push_frame(frame.time_us, frame.positions.data()).characters_settled;
        settled += annotator->finish_work().characters_settled;
        annotator->flush();
        const Counts after = snapshot();
        Eigen::internal::set_is_malloc_allowed(true);

        CHECK(settled > 100);
        CHECK(after.mallocs == before.mallocs);
        CHECK(after.news == before.news);
        CHECK(after.eigen == before.eigen);
    }
}

TEST_CASE("classifying and scoring whole clips with votes, exemplars and a clip descriptor allocates nothing") {
    actionstring::host::ToyWorld world = actionstring::host::make_toy_world();
    const auto train = actionstring::host::toy_clips(world, 6, 100);
    actionstring::host::TrainingOptions options = test::toy_options();
    options.components = 0;
    options.pca_dim = 6;
    options.exemplars = 4;
    options.exemplar_weight = 1.0;
    options.descriptor_levels = 2;
    options.descriptor_weight = 1.0;
    options.direction_levels = 2;
    options.direction_weight = 1.0;
    const actionstring::host::ModelData model = actionstring::host::train_model(train, options);
    const actionstring::ModelView view = model.view();
    REQUIRE(view.has_exemplars());
    REQUIRE(view.has_descriptor());
    REQUIRE(view.has_directions());
    // Each clip's characters and features, collected before the measurement.
    std::vector<std::vector<actionstring::Character>> strings;
    std::vector<std::vector<float>> features, records;
    std::size_t longest = 0;
    for (const auto& c : actionstring::host::toy_clips(world, 2, 9000, 30.0)) {
        actionstring::host::Stateful<actionstring::StringEncoder> encoder;
        REQUIRE(encoder.init(view, actionstring::EncoderConfig{}) == actionstring::Status::ok);
        strings.emplace_back();
        features.emplace_back();
        records.emplace_back();
        for (std::size_t f = 0; f < c.clip.frame_count(); ++f) {
            const auto e = encoder->push_frame(static_cast<std::int64_t>(c.clip.times[f] * 1e6), c.clip.frame(f));
            for (std::uint32_t k = 0; k < e.count(); ++k) {
                const bool previous = k < e.from_previous;
                strings.back().push_back(previous ? e.previous : e.current);
                const float* x = previous ? e.previous_feature : e.current_feature;
                features.back().insert(features.back().end(), x, x + view.feature_dim);
                const float* pose = previous ? e.previous_pose : e.current_pose;
                const float* facing = previous ? e.previous_facing : e.current_facing;
                records.back().insert(records.back().end(), pose, pose + view.pose_dim());
                records.back().insert(records.back().end(), facing, facing + 2);
            }
        }
        longest = std::max(longest, strings.back().size());
    }
    std::vector<float> scratch(actionstring::clip_scratch_floats(view)), scores(view.label_count);
    std::vector<actionstring::detail::Cell> cells(actionstring::clip_cells(view, longest));

    Eigen::internal::set_is_malloc_allowed(false);
    const Counts before = snapshot();
    std::size_t labelled = 0, scored = 0;
    for (std::size_t i = 0; i < strings.size(); ++i) {
        labelled += actionstring::classify_clip(view, strings[i].data(), features[i].data(), records[i].data(),
                                                strings[i].size(), scratch.data(), cells.data())
                        .label != actionstring::unknown_label;
        actionstring::clip_label_distances(view, strings[i].data(), features[i].data(), records[i].data(),
                                           strings[i].size(), scratch.data(), cells.data(), scores.data());
        scored += std::isfinite(*std::min_element(scores.begin(), scores.end()));
    }
    const Counts after = snapshot();
    Eigen::internal::set_is_malloc_allowed(true);

    CHECK(labelled > 0);
    CHECK(scored == strings.size());
    CHECK(after.mallocs == before.mallocs);
    CHECK(after.news == before.news);
    CHECK(after.eigen == before.eigen);
}
