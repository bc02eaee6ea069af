// The order of a GMM's components in the model: co-live components share a block.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <vector>

#include "actionstring/gmm.hpp"
#include "model/model_data.hpp"
#include "train/gmm_order.hpp"

using namespace actionstring;

namespace {

// Two far-apart groups of four components each, interleaved by index: A = {0, 2, 5, 7}
// around x = 0 and B = {1, 3, 4, 6} around x = 50 (unit variances, so across the
// groups the log joints differ by about 1,250, far beyond exp's underflow).
struct TwoGroups {
    std::vector<Eigen::VectorXd> means;
    std::vector<Eigen::MatrixXd> covariances;
    std::vector<double> weights;
    host::ModelData data;
};

TwoGroups two_groups(Covariance kind) {
    TwoGroups g;
    const int group_of[8] = {0, 1, 0, 1, 1, 0, 1, 0};
    for (int j = 0; j < 8; ++j) {
        Eigen::VectorXd mean(2);
        mean << 50.0 * group_of[j] + 0.3 * (j % 3), 0.2 * j;
        g.means.push_back(mean);
        g.covariances.push_back(Eigen::MatrixXd::Identity(2, 2));
        g.weights.push_back(1.0 / 8.0);
    }
    host::set_gmm(g.data, g.means, g.covariances, g.weights, kind);
    return g;
}

// Poses near each group's centre; `near_a` of them near A, `near_b` near B.
Eigen::MatrixXd samples(int near_a, int near_b) {
    std::mt19937 rng(7);
    std::normal_distribution<double> normal(0.0, 0.5);
    Eigen::MatrixXd s(2, near_a + near_b);
    for (int i = 0; i < near_a + near_b; ++i) {
        s(0, i) = (i < near_a ? 0.3 : 50.3) + normal(rng);
        s(1, i) = 0.7 + normal(rng);
    }
    return s;
}

}  // namespace

TEST_CASE("gmm_block_order puts components live on the same poses in one block") {
    for (const Covariance kind : {Covariance::full, Covariance::diagonal}) {
        const TwoGroups g = two_groups(kind);
        // A is live more often, so its block comes first; within a block, the
        // most often live component leads and equal counts go to the lower index.
        std::vector<std::size_t> order = host::gmm_block_order(g.data.view(), samples(30, 20));
        std::vector<std::size_t> first(order.begin(), order.begin() + 4), second(order.begin() + 4, order.end());
        std::sort(first.begin(), first.end());
        std::sort(second.begin(), second.end());
        CHECK(first == std::vector<std::size_t>{0, 2, 5, 7});
        CHECK(second == std::vector<std::size_t>{1, 3, 4, 6});
        // The other way round when B is live more often.
        order = host::gmm_block_order(g.data.view(), samples(20, 30));
        first.assign(order.begin(), order.begin() + 4);
        std::sort(first.begin(), first.end());
        CHECK(first == std::vector<std::size_t>{1, 3, 4, 6});
        // Deterministic: the same input, the same order.
        CHECK(host::gmm_block_order(g.data.view(), samples(20, 30)) == order);
    }
}

TEST_CASE("gmm_block_order: a permutation, the identity for one block, refuses a wrong dimension") {
    const TwoGroups g = two_groups(Covariance::full);
    std::vector<std::size_t> order = host::gmm_block_order(g.data.view(), samples(5, 5));
    std::sort(order.begin(), order.end());
    for (std::size_t j = 0; j < order.size(); ++j) CHECK(order[j] == j);

    host::ModelData small;
    host::set_gmm(small, {g.means.begin(), g.means.begin() + 3}, {g.covariances.begin(), g.covariances.begin() + 3},
                  {1.0 / 3, 1.0 / 3, 1.0 / 3}, Covariance::full);
    CHECK(host::gmm_block_order(small.view(), samples(5, 5)) == std::vector<std::size_t>{0, 1, 2});

    CHECK_THROWS_AS(host::gmm_block_order(g.data.view(), Eigen::MatrixXd::Zero(3, 4)), std::invalid_argument);
}

TEST_CASE("a GMM in block order is the same mixture: each component's log joint keeps its bits") {
    const TwoGroups g = two_groups(Covariance::full);
    const std::vector<std::size_t> order = host::gmm_block_order(g.data.view(), samples(30, 20));
    TwoGroups ordered;
    for (const std::size_t j : order) {
        ordered.means.push_back(g.means[j]);
        ordered.covariances.push_back(g.covariances[j]);
        ordered.weights.push_back(g.weights[j]);
    }
    host::set_gmm(ordered.data, ordered.means, ordered.covariances, ordered.weights, Covariance::full);
    const ModelView a = g.data.view(), b = ordered.data.view();
    std::vector<float> joint_a(8), joint_b(8), scratch_a(gmm_scratch_floats(a)), scratch_b(gmm_scratch_floats(b));
    const Eigen::MatrixXd s = samples(10, 10);
    for (Eigen::Index i = 0; i < s.cols(); ++i) {
        const float feature[2] = {static_cast<float>(s(0, i)), static_cast<float>(s(1, i))};
        REQUIRE(gmm_log_joint(a, feature, joint_a.data(), scratch_a.data()) == Status::ok);
        REQUIRE(gmm_log_joint(b, feature, joint_b.data(), scratch_b.data()) == Status::ok);
        for (std::size_t k = 0; k < 8; ++k) CHECK(detail::to_bits(joint_b[k]) == detail::to_bits(joint_a[order[k]]));
    }
}
