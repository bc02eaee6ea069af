// The tree descent's distances follow their stated order of additions on every
// path: this file is built into the unit tests (SSE lanes on x86-64) and into
// the scalar-path tests (what a Cortex-M4 runs), and both must give the bits
// of the reference below, written out term by term.
#include <doctest/doctest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
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
