// Incremental matcher == batch reference, bit for bit, over random cases.
#include <doctest/doctest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "actionstring/matcher.hpp"
#include "run/state.hpp"
#include "test_support.hpp"

using namespace actionstring;

namespace {

// Owns the matching tables of a random model.
struct RandomMatching {
    std::vector<float> w;
    std::vector<std::uint32_t> offsets{0};
    std::vector<Character> strings;
    std::vector<LabelId> labels;
    static constexpr char names_text[] = "only";
    static constexpr std::uint32_t names_offsets[2] = {0, 5};
    ModelView view;
};

void fill(RandomMatching& m, std::mt19937& rng, MatchVariant variant, LengthNormalization normalization) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    const int K = uniform(1, 12);
    // Small integers make equal costs, and so tie-breaking, common; some W asymmetric.
    const bool integers = uniform(0, 1) == 0;
    m.w.resize(static_cast<std::size_t>(K * K));
    for (auto& x : m.w)
        x = integers ? static_cast<float>(uniform(0, 3)) : std::uniform_real_distribution<float>(0.0f, 2.0f)(rng);
    const int R = uniform(1, 6);
    for (int r = 0; r < R; ++r) {
        const int length = uniform(1, 40);
        for (int i = 0; i < length; ++i) m.strings.push_back(static_cast<Character>(uniform(0, K - 1)));
        m.offsets.push_back(static_cast<std::uint32_t>(m.strings.size()));
        m.labels.push_back(0);
    }
    ModelView& v = m.view;
    v.character_count = static_cast<std::uint16_t>(K);
    v.character_distances = m.w.data();
    v.representative_count = static_cast<std::uint16_t>(R);
    v.representative_offsets = m.offsets.data();
    v.representative_chars = m.strings.data();
    v.representative_labels = m.labels.data();
    v.label_count = 1;
    v.label_names = NameTable{m.names_text, m.names_offsets};
    v.variant = variant;
    v.normalization = normalization;
    v.window_chars = static_cast<std::uint16_t>(uniform(1, 30));
    const int longest_step = v.window_chars + 3;  // steps past the window leave gaps
    v.step_chars = static_cast<std::uint16_t>(uniform(1, longest_step));
    v.neighbours = 1;
}

void check_against_batch(MatchVariant variant, LengthNormalization normalization, int cases, std::uint32_t seed,
                         long& windows_checked, long& both_orientations) {
    std::mt19937 rng(seed);
    host::Stateful<WindowMatcher> matcher;
    for (int c = 0; c < cases; ++c) {
        RandomMatching m;
        fill(m, rng, variant, normalization);
        REQUIRE(matcher.init(m.view) == Status::ok);
        const int K = m.view.character_count;
        const int length = std::uniform_int_distribution<int>(0, 120)(rng);
        std::vector<Character> stream;
        bool window_shorter = false, window_longer = false;
        for (int i = 0; i < length; ++i) {
            stream.push_back(static_cast<Character>(std::uniform_int_distribution<int>(0, K - 1)(rng)));
            if (!matcher->push(stream.back())) continue;
            const auto start = static_cast<std::size_t>(matcher->completed_window_start());
            REQUIRE(start + m.view.window_chars == stream.size());
            const std::vector<Character> window(stream.begin() + static_cast<long>(start), stream.end());
            for (std::size_t r = 0; r < m.view.representative_count; ++r) {
                const std::vector<Character> rep(m.strings.begin() + m.offsets[r],
                                                 m.strings.begin() + m.offsets[r + 1]);
                (window.size() <= rep.size() ? window_shorter : window_longer) = true;
                const float expected =
                    test::batch_distance(window, rep, m.w, static_cast<std::size_t>(K), variant, normalization);
                const float got = matcher->completed_distances()[r];
                if (!test::same_bits(expected, got)) {
                    FAIL("case " << c << " rep " << r << " window@" << start << ": incremental " << got << " != batch "
                                 << expected);
                }
            }
            ++windows_checked;
        }
        both_orientations += window_shorter && window_longer;
    }
}

}  // namespace

TEST_CASE("completed windows equal the batch distance bit for bit") {
    const MatchVariant variants[] = {MatchVariant::paper, MatchVariant::whole, MatchVariant::subsequence};
    const LengthNormalization norms[] = {LengthNormalization::none, LengthNormalization::path,
                                         LengthNormalization::query};
    std::uint32_t seed = 100;
    for (const auto variant : variants)
        for (const auto norm : norms) {
            CAPTURE(static_cast<int>(variant));
            CAPTURE(static_cast<int>(norm));
            long windows = 0, mixed = 0;
            check_against_batch(variant, norm, 400, seed++, windows, mixed);
            // The random cases must exercise many windows and both orientations.
            CHECK(windows > 2000);
            CHECK(mixed > 20);
        }
}

TEST_CASE("windows start every step and complete after window characters") {
    RandomMatching m;
    std::mt19937 rng(3);
    fill(m, rng, MatchVariant::whole, LengthNormalization::none);
    m.view.window_chars = 6;
    m.view.step_chars = 2;
    host::Stateful<WindowMatcher> matcher;
    REQUIRE(matcher.init(m.view) == Status::ok);
    std::vector<std::size_t> completions;
    for (std::size_t i = 0; i < 20; ++i)
        if (matcher->push(0)) completions.push_back(i);
    // Windows start at 0, 2, 4, …, each completes 5 characters later.
    const std::vector<std::size_t> expected = {5, 7, 9, 11, 13, 15, 17, 19};
    CHECK(completions == expected);
    CHECK(matcher->completed_window_start() == 14);
    matcher->reset();
    CHECK(matcher->characters_pushed() == 0);
    CHECK_FALSE(matcher->has_completed_window());
}

TEST_CASE("the matcher's storage follows the model: exact size, alignment, refusals") {
    RandomMatching m;
    std::mt19937 rng(4);
    fill(m, rng, MatchVariant::whole, LengthNormalization::path);
    const std::size_t with_paths = WindowMatcher::required_bytes(m.view);
    m.view.normalization = LengthNormalization::none;
    const std::size_t without_paths = WindowMatcher::required_bytes(m.view);
    CHECK(without_paths < with_paths);  // path lengths are kept only when the model divides by them
    m.view.window_chars = 64;
    m.view.step_chars = 1;  // 64 windows open at once: 64 lanes
    const std::size_t many_lanes = WindowMatcher::required_bytes(m.view);
    CHECK(many_lanes > 8 * without_paths);
    CHECK(many_lanes % state_alignment == 0);

    alignas(state_alignment) static unsigned char block[1 << 20];
    REQUIRE(many_lanes + state_alignment <= sizeof block);
    WindowMatcher matcher;
    CHECK(matcher.init(m.view, block, many_lanes - 1) == Status::storage_too_small);
    CHECK_FALSE(matcher.push(0));  // unusable after a failed init, and says so by doing nothing
    CHECK(matcher.init(m.view, block + 4, many_lanes) == Status::storage_too_small);  // misaligned
    CHECK(matcher.init(m.view, nullptr, many_lanes) == Status::storage_too_small);
    REQUIRE(matcher.init(m.view, block, many_lanes) == Status::ok);
    for (int i = 0; i < 200; ++i) matcher.push(static_cast<Character>(i % m.view.character_count));
    CHECK(matcher.has_completed_window());
    m.view.step_chars = 0;
    CHECK(matcher.init(m.view, block, sizeof block) == Status::invalid_model);
}
