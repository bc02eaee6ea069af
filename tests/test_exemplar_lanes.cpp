// The exemplars' distances carry the same bits on every path: four centres in
// SIMD lanes on x86-64, the scalar loop a Cortex-M4 runs (this file is also
// built into the scalar-path tests), and eight-lane builds. Each centre's sum
// is checked against a reference written from the documented order, not from
// the code: four partial sums over j ≡ k (mod 4), then (s0 + s1) + (s2 + s3).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "actionstring/exemplars.hpp"

using namespace actionstring;

namespace {

float reference_distance(const float* x, const float* c, std::size_t d) {
    float partial[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (std::size_t j = 0; j < d; ++j) partial[j % 4] += (x[j] - c[j]) * (x[j] - c[j]);
    return (partial[0] + partial[1]) + (partial[2] + partial[3]);
}

float in_order_distance(const float* x, const float* c, std::size_t d) {
    float sum = 0.0f;
    for (std::size_t j = 0; j < d; ++j) sum += (x[j] - c[j]) * (x[j] - c[j]);
    return sum;
}

// A view of exemplars alone: `labels` and `centres` (feature_dim floats each) must outlive it.
ModelView exemplar_view(std::size_t label_count, std::size_t d, const std::vector<LabelId>& labels,
                        const std::vector<float>& centres) {
    ModelView view{};
    view.label_count = static_cast<std::uint16_t>(label_count);
    view.feature_dim = static_cast<std::uint16_t>(d);
    view.exemplar_count = static_cast<std::uint16_t>(labels.size());
    view.exemplar_labels = labels.data();
    view.exemplars = centres.data();
    return view;
}

}  // namespace

TEST_CASE("exemplar distances: the documented order, bit for bit, for every dimension and centre count") {
    std::mt19937 rng(11);
    // Coordinates of mixed magnitudes, so that another order of the same
    // additions rounds differently (counted below: the check can fail).
    std::normal_distribution<float> normal(0.0f, 1.0f);
    std::uniform_real_distribution<float> magnitude(-3.0f, 3.0f);
    auto coordinate = [&] { return normal(rng) * std::pow(10.0f, magnitude(rng)); };
    std::size_t order_mattered = 0, compared = 0;
    for (const std::size_t d : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 12u, 13u, 24u, 31u}) {
        for (const std::size_t n : {1u, 3u, 4u, 5u, 8u, 9u, 17u, 64u}) {
            const std::size_t L = 4;  // label 3 has no centres
            std::vector<float> centres(n * d), feature(d);
            std::vector<LabelId> labels(n);
            for (float& v : centres) v = coordinate();
            for (float& v : feature) v = coordinate();
            for (std::size_t e = 0; e < n; ++e) labels[e] = static_cast<LabelId>(rng() % 3);
            const ModelView view = exemplar_view(L, d, labels, centres);
            std::vector<float> expected(L, std::numeric_limits<float>::infinity()), got(L, 0.0f);
            for (std::size_t e = 0; e < n; ++e) {
                const float s = reference_distance(feature.data(), &centres[e * d], d);
                if (s < expected[labels[e]]) expected[labels[e]] = s;
                order_mattered += s != in_order_distance(feature.data(), &centres[e * d], d);
                ++compared;
            }
            exemplar_distances(view, feature.data(), got.data());
            CAPTURE(d);
            CAPTURE(n);
            CHECK(std::memcmp(expected.data(), got.data(), L * sizeof(float)) == 0);
            CHECK(got[3] == std::numeric_limits<float>::infinity());
        }
    }
    CHECK(order_mattered > compared / 10);
}

TEST_CASE("exemplar distances: a model's exemplar_dim leading coordinates, the rest of the feature unread") {
    std::mt19937 rng(5);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    for (const std::size_t k : {1u, 3u, 4u, 5u, 8u, 12u, 13u}) {
        const std::size_t d = k + 1 + k % 5, n = 37, L = 3;
        std::vector<float> centres(n * k), feature(d);
        std::vector<LabelId> labels(n);
        for (float& v : centres) v = normal(rng);
        for (float& v : feature) v = normal(rng);
        for (std::size_t e = 0; e < n; ++e) labels[e] = static_cast<LabelId>(e * L / n);  // label by label
        ModelView view = exemplar_view(L, d, labels, centres);
        view.exemplar_dim = static_cast<std::uint16_t>(k);
        REQUIRE(view.exemplar_dims() == k);
        std::vector<float> expected(L, std::numeric_limits<float>::infinity()), got(L, 0.0f);
        for (std::size_t e = 0; e < n; ++e) {
            const float s = reference_distance(feature.data(), &centres[e * k], k);
            if (s < expected[labels[e]]) expected[labels[e]] = s;
        }
        exemplar_distances(view, feature.data(), got.data());
        CAPTURE(k);
        CHECK(std::memcmp(expected.data(), got.data(), L * sizeof(float)) == 0);
        // The coordinates past k do not count.
        for (std::size_t j = k; j < d; ++j) feature[j] = 1e6f;
        exemplar_distances(view, feature.data(), got.data());
        CHECK(std::memcmp(expected.data(), got.data(), L * sizeof(float)) == 0);
    }
}

TEST_CASE("exemplar distances: centres stored label by label, in runs of any length, pieces in any split") {
    // The nearest of a run of one label's centres is kept in a register and
    // written once (detail::NearestRun): runs that start and end inside a
    // block of four, "no action"'s centres (asked for or not), a label beyond
    // the model's (never wanted), and the centres taken in uneven pieces.
    std::mt19937 rng(5);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    std::size_t compared = 0;
    for (const std::size_t d : {3u, 8u, 13u, 24u}) {
        for (int trial = 0; trial < 30; ++trial) {
            const std::size_t L = 4;
            std::vector<LabelId> labels;
            for (std::size_t l = 0; l < L + 2; ++l) {
                const LabelId id = l < L    ? static_cast<LabelId>(l)
                                   : l == L ? unknown_label
                                            : static_cast<LabelId>(L + 3);
                const std::size_t run = static_cast<std::size_t>(rng() % 11);  // 0 … 10 centres
                labels.insert(labels.end(), run, id);
            }
            if (trial % 3 == 0) std::shuffle(labels.begin(), labels.end(), rng);  // and no order at all
            const std::size_t n = labels.size();
            std::vector<float> centres(n * d), feature(d);
            for (float& v : centres) v = normal(rng);
            for (float& v : feature) v = normal(rng);
            const ModelView view = exemplar_view(L, d, labels, centres);
            const float inf = std::numeric_limits<float>::infinity();
            std::vector<float> expected(L, inf);
            float expected_none = inf;
            for (std::size_t e = 0; e < n; ++e) {
                const float s = reference_distance(feature.data(), &centres[e * d], d);
                if (labels[e] < L && s < expected[labels[e]]) expected[labels[e]] = s;
                if (labels[e] == unknown_label && s < expected_none) expected_none = s;
            }
            std::vector<float> got(L, 0.0f);
            float none = 0.0f;
            exemplar_distances(view, feature.data(), got.data(), &none);
            CHECK(std::memcmp(expected.data(), got.data(), L * sizeof(float)) == 0);
            CHECK(std::memcmp(&expected_none, &none, sizeof none) == 0);
            exemplar_distances(view, feature.data(), got.data());  // "no action" not asked for
            CHECK(std::memcmp(expected.data(), got.data(), L * sizeof(float)) == 0);
            std::vector<float> pieces(L, inf);
            float pieces_none = inf;
            for (std::size_t first = 0; first < n;) {
                const std::size_t last = std::min(n, first + 1 + static_cast<std::size_t>(rng() % 7));
                nearest_exemplars(view, feature.data(), first, last, pieces.data(), &pieces_none);
                first = last;
            }
            CHECK(std::memcmp(expected.data(), pieces.data(), L * sizeof(float)) == 0);
            CHECK(std::memcmp(&expected_none, &pieces_none, sizeof none) == 0);
            ++compared;
        }
    }
    CHECK(compared == 120);
}
