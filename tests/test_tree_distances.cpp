// The tree descent's distances follow their stated order of additions on every
// path: this file is built into the unit tests (SSE lanes on x86-64) and into
// the scalar-path tests (what a Cortex-M4 runs), and both must give the bits
// of the reference below, written out term by term.
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "actionstring/tree.hpp"

using namespace actionstring;

namespace {

std::uint32_t bits_of(float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

// tree.hpp's definition: part k sums the squared differences of j ≡ k (mod 4)
// in increasing j; the distance is (part 0 + part 1) + (part 2 + part 3).
float reference_distance_sq(const float* feature, const float* centroid, std::size_t dim) {
    float part[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (std::size_t j = 0; j < dim; ++j) {
        const float d = feature[j] - centroid[j];
        part[j % 4] += d * d;
    }
    return (part[0] + part[1]) + (part[2] + part[3]);
}

// A model of three nodes (a root and two leaves) in `dim` dimensions, without a GMM.
struct TinyTree {
    std::vector<float> centroids;
    std::vector<std::int16_t> children{1, 2, -1, -1, -1, -1};
    std::vector<Character> characters{0, 0, 1};
    ModelView view{};
    TinyTree(std::size_t dim, std::mt19937& rng) {
        std::normal_distribution<float> normal(0.0f, 3.0f);
        centroids.resize(3 * dim);
        for (float& v : centroids) v = normal(rng);
        view.feature_dim = static_cast<std::uint16_t>(dim);
        view.node_count = 3;
        view.node_centroids = centroids.data();
        view.node_children = children.data();
        view.node_characters = characters.data();
    }
};

}  // namespace

TEST_CASE("tree distances: the stated order of additions, bit for bit, at every dimension") {
    std::mt19937 rng(11);
    std::normal_distribution<float> normal(0.0f, 3.0f);
    for (std::size_t dim = 1; dim <= 45; ++dim) {
        CAPTURE(dim);
        TinyTree tree(dim, rng);
        for (int trial = 0; trial < 20; ++trial) {
            std::vector<float> feature(dim);
            for (float& v : feature) v = normal(rng);
            float to_left = -1.0f, to_right = -1.0f;
            node_distances_sq(tree.view, 1, 2, feature.data(), to_left, to_right);
            const float want_left = reference_distance_sq(feature.data(), tree.centroids.data() + dim, dim);
            const float want_right = reference_distance_sq(feature.data(), tree.centroids.data() + 2 * dim, dim);
            CHECK(bits_of(to_left) == bits_of(want_left));
            CHECK(bits_of(to_right) == bits_of(want_right));
            // The descent takes the nearer child, the left one on a tie.
            const Character expected = want_right < want_left ? 1 : 0;
            CHECK(descend_tree(tree.view, feature.data()) == expected);
        }
    }
}

TEST_CASE("tree descent: a feature on a centroid goes to it; equidistant goes left") {
    std::mt19937 rng(12);
    for (std::size_t dim : {std::size_t{3}, std::size_t{8}, std::size_t{40}}) {
        CAPTURE(dim);
        TinyTree tree(dim, rng);
        const float* left = tree.centroids.data() + dim;
        const float* right = tree.centroids.data() + 2 * dim;
        CHECK(descend_tree(tree.view, left) == 0);
        CHECK(descend_tree(tree.view, right) == 1);
        // Both children at the same place: a tie, and ties go left.
        std::memcpy(tree.centroids.data() + 2 * dim, left, dim * sizeof(float));
        CHECK(descend_tree(tree.view, right) == 0);
    }
}

namespace {

// A random full binary tree of `leaves` leaves over posterior-like centroids
// (non-negative, few large coordinates), children after their parent.
struct RandomTree {
    std::size_t dim;
    std::vector<float> centroids;
    std::vector<std::int16_t> children;
    std::vector<Character> characters;
    std::vector<float> norms;
    ModelView view{};
    RandomTree(std::size_t dim_, int leaves, std::mt19937& rng) : dim(dim_) {
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::uniform_int_distribution<std::size_t> coordinate(0, dim - 1);
        // Grow by splitting a random leaf until there are `leaves`.
        children = {-1, -1};
        std::vector<std::size_t> open{0};
        while (open.size() < static_cast<std::size_t>(leaves)) {
            const std::size_t pick = std::uniform_int_distribution<std::size_t>(0, open.size() - 1)(rng);
            const std::size_t node = open[pick];
            const auto left = static_cast<std::int16_t>(children.size() / 2);
            children[2 * node] = left;
            children[2 * node + 1] = static_cast<std::int16_t>(left + 1);
            children.insert(children.end(), {-1, -1, -1, -1});
            open[pick] = static_cast<std::size_t>(left);
            open.push_back(static_cast<std::size_t>(left) + 1);
        }
        const std::size_t nodes = children.size() / 2;
        centroids.assign(nodes * dim, 0.0f);
        for (std::size_t n = 0; n < nodes; ++n) {
            float* c = centroids.data() + n * dim;
            for (std::size_t j = 0; j < dim; ++j) c[j] = unit(rng) < 0.7f ? 0.02f * unit(rng) : 0.0f;
            for (int k = 0; k < 3; ++k) c[coordinate(rng)] += unit(rng);
        }
        characters.assign(nodes, 0);
        Character next = 0;
        for (std::size_t n = 0; n < nodes; ++n)
            if (children[2 * n] < 0) characters[n] = next++;
        view.feature_dim = static_cast<std::uint16_t>(dim);
        view.node_count = static_cast<std::uint16_t>(nodes);
        view.node_centroids = centroids.data();
        view.node_children = children.data();
        view.node_characters = characters.data();
        norms.resize(tree_norm_floats(view));
        tree_node_norms(view, norms.data());
    }
    Character sparse(const std::vector<float>& feature) const {
        std::vector<std::uint16_t> nonzero(dim);
        return descend_tree_sparse(view, feature.data(), norms.data(), nonzero.data());
    }
};

// A posterior-like feature: `count` non-zero coordinates summing to about 1.
std::vector<float> sparse_feature(std::size_t dim, std::size_t count, std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_int_distribution<std::size_t> coordinate(0, dim - 1);
    std::vector<float> feature(dim, 0.0f);
    float total = 0.0f;
    for (std::size_t k = 0; k < count; ++k) {
        const float v = unit(rng) < 0.2f ? 1e-30f * unit(rng) : unit(rng);  // some far below the rest
        feature[coordinate(rng)] += v;
        total += v;
    }
    if (total > 0.0f)
        for (float& v : feature) v /= total;
    return feature;
}

}  // namespace

TEST_CASE("sparse tree descent: the dense descent's character on every feature") {
    std::mt19937 rng(21);
    for (std::size_t dim : {std::size_t{1}, std::size_t{5}, std::size_t{20}, std::size_t{40}, std::size_t{64},
                            std::size_t{257}}) {
        CAPTURE(dim);
        for (int t = 0; t < 6; ++t) {
            const RandomTree tree(dim, 2 + t * 9, rng);
            for (int trial = 0; trial < 300; ++trial) {
                // Mostly sparse, sometimes a third non-zero (still the sparse path), sometimes
                // dense (more than half non-zero: the dense descent at once).
                const std::size_t count = trial % 10 == 9   ? dim
                                          : trial % 10 == 8 ? 1 + dim / 3
                                                            : 1 + static_cast<std::size_t>(trial) % 6;
                const std::vector<float> feature = sparse_feature(dim, count, rng);
                CHECK(tree.sparse(feature) == descend_tree(tree.view, feature.data()));
            }
        }
    }
}

TEST_CASE("sparse tree descent: near ties and exact ties decide as the dense descent does") {
    std::mt19937 rng(22);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (std::size_t dim : {std::size_t{8}, std::size_t{40}}) {
        CAPTURE(dim);
        RandomTree tree(dim, 2, rng);  // a root and two leaves: 1 (character 0), 2 (character 1)
        float* a = tree.centroids.data() + dim;
        float* b = tree.centroids.data() + 2 * dim;
        std::size_t right = 0, total = 0;
        for (int trial = 0; trial < 2000; ++trial) {
            // b is a with two coordinates p, q swapped, and the feature equal at p and q:
            // the exact distances tie, so float rounding alone decides the dense descent.
            for (std::size_t j = 0; j < dim; ++j) a[j] = unit(rng) < 0.5f ? unit(rng) : 0.0f;
            std::memcpy(b, a, dim * sizeof(float));
            const std::size_t p = static_cast<std::size_t>(trial) % dim, q = (p + 1 + static_cast<std::size_t>(trial) / dim) % dim;
            std::swap(b[p], b[q]);
            std::vector<float> feature = sparse_feature(dim, 2, rng);
            feature[q] = feature[p] = unit(rng) < 0.3f ? 0.0f : unit(rng);
            // Half the time, nudge one centroid coordinate by an ulp: a near tie.
            if (trial % 2 == 1) b[p] = std::nextafter(b[p], trial % 4 == 1 ? 2.0f : -1.0f);
            tree_node_norms(tree.view, tree.norms.data());
            const Character dense = descend_tree(tree.view, feature.data());
            CHECK(tree.sparse(feature) == dense);
            right += dense;
            ++total;
        }
        // Both outcomes occur, so a sparse rule that only sent ties left would fail above.
        CHECK(right > 0);
        CHECK(right < total);
    }
}
