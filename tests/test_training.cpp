// Training: EM, the ε tree, agglomeration, determinism, artifact IO and codegen.
#include <doctest/doctest.h>

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <thread>
#include <string>

#include "actionstring/annotator.hpp"
#include "actionstring/exemplars.hpp"
#include "actionstring/string_distance.hpp"
#include "io/recordings.hpp"
#include "model/artifact.hpp"
#include "model/header.hpp"
#include "io/stream.hpp"
#include "train/clustering.hpp"
#include "toy/toy.hpp"
#include "run/classify.hpp"
#include "common/parallel.hpp"
#include "run/encode.hpp"
#include "run/state.hpp"
#include "train/gmm_em.hpp"
#include "train/pca.hpp"
#include "train/pipeline.hpp"
#include "train/exemplars.hpp"
#include "train/rejection.hpp"
#include "toy_options.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

Eigen::MatrixXd blobs(int per_blob, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.2);
    const double centres[3][2] = {{0, 0}, {3, 0}, {0, 4}};
    Eigen::MatrixXd x(2, 3 * per_blob);
    for (int b = 0; b < 3; ++b)
        for (int i = 0; i < per_blob; ++i) {
            x(0, b * per_blob + i) = centres[b][0] + noise(rng) * (b + 1);
            x(1, b * per_blob + i) = centres[b][1] + noise(rng);
        }
    return x;
}

using test::toy_options;

// The toy options without a GMM: characters on the projected poses.
TrainingOptions toy_pca_only_options() {
    TrainingOptions o = toy_options();
    o.components = 0;
    o.pca_dim = 6;
    o.epsilon = 0.5;
    o.sigma = 0.5;
    return o;
}

}  // namespace

TEST_CASE("EM: the penalised log-likelihood never decreases and the blobs are found") {
    for (const Covariance kind : {Covariance::full, Covariance::diagonal}) {
        // Strongly overlapping clusters: EM needs many iterations, each checked.
        std::mt19937 rng(4);
        std::normal_distribution<double> noise(0.0, 0.6);
        Eigen::MatrixXd overlapping(2, 900);
        for (int i = 0; i < 900; ++i) {
            overlapping(0, i) = (i % 3 == 1 ? 1.0 : 0.0) + noise(rng);
            overlapping(1, i) = (i % 3 == 2 ? 1.2 : 0.0) + 0.5 * noise(rng);
        }
        const GmmFit slow = fit_gmm(overlapping, 3, kind, 1e-3, 300, 1e-12, 5);
        REQUIRE(slow.report.objective.size() > 10);
        CHECK(slow.report.reseeded.empty());
        for (std::size_t i = 1; i < slow.report.objective.size(); ++i)
            CHECK(slow.report.objective[i] >=
                  slow.report.objective[i - 1] - 1e-9 * std::fabs(slow.report.objective[i - 1]));
        const GmmFit fit = fit_gmm(blobs(200, 3), 3, kind, 1e-3, 200, 1e-10, 5);
        CHECK(fit.report.converged);
        std::set<int> found;
        for (const auto& mean : fit.means)
            found.insert(static_cast<int>(std::lround(mean[0])) * 10 + static_cast<int>(std::lround(mean[1])));
        CHECK(found == std::set<int>{0, 30, 4});
        for (double w : fit.weights) CHECK(w == doctest::Approx(1.0 / 3).epsilon(0.05));
    }
}

TEST_CASE("parallel_for: every job once, nested loops inline, the lowest failure rethrown") {
    for (const std::size_t workers : {std::size_t{1}, std::size_t{3}, std::size_t{16}}) {
        std::vector<int> runs(10, 0);
        std::vector<std::vector<int>> inner(10, std::vector<int>(4, 0));
        std::vector<std::vector<char>> same_thread(10, std::vector<char>(4, 0));
        parallel_for(runs.size(), workers, [&](std::size_t k) {
            ++runs[k];
            // Nested inside a started thread: runs on that thread. (With one
            // worker the outer loop is inline and the inner one may use threads.)
            const std::thread::id here = std::this_thread::get_id();
            parallel_for(4, 4, [&](std::size_t i) {
                same_thread[k][i] = std::this_thread::get_id() == here;
                ++inner[k][i];
            });
        });
        CHECK(runs == std::vector<int>(10, 1));
        for (std::size_t k = 0; k < 10; ++k) {
            CHECK(inner[k] == std::vector<int>(4, 1));
            if (workers > 1) CHECK(same_thread[k] == std::vector<char>(4, 1));
        }
        try {
            parallel_for(10, workers, [](std::size_t k) {
                if (k == 7 || k == 4) throw std::runtime_error("job " + std::to_string(k));
            });
            FAIL("no exception");
        } catch (const std::runtime_error& error) {
            CHECK(std::string(error.what()) == "job 4");
        }
    }
}

TEST_CASE("EM: the same fit on any number of workers, and a progress report per iteration") {
    for (const Covariance kind : {Covariance::full, Covariance::diagonal}) {
        // Re-seeds and drops included: more components than the blobs support.
        Eigen::MatrixXd x = blobs(300, 4);
        x.row(0) *= 0.3;
        const GmmFit one = fit_gmm(x, 8, kind, 1e-3, 300, 1e-12, 5, 1);
        std::vector<EmProgress> steps;
        const GmmFit three =
            fit_gmm(x, 8, kind, 1e-3, 300, 1e-12, 5, 3, [&](const EmProgress& step) { steps.push_back(step); });
        REQUIRE(one.means.size() == three.means.size());
        CHECK(one.report.objective == three.report.objective);  // exactly: the sums keep their order
        CHECK(one.report.reseeded == three.report.reseeded);
        for (std::size_t j = 0; j < one.means.size(); ++j) {
            CHECK(one.means[j] == three.means[j]);
            CHECK(one.covariances[j] == three.covariances[j]);
            CHECK(one.weights[j] == three.weights[j]);
        }
        // One report per iteration, in order, the last one saying whether EM converged.
        REQUIRE(steps.size() == three.report.objective.size());
        for (std::size_t i = 0; i < steps.size(); ++i) {
            CHECK(steps[i].iteration == static_cast<int>(i));
            CHECK(steps[i].max_iterations == 300);
            CHECK(steps[i].objective == three.report.objective[i]);
            CHECK(steps[i].converged == (i + 1 == steps.size() && three.report.converged));
            const bool reseeded = std::find(three.report.reseeded.begin(), three.report.reseeded.end(),
                                            static_cast<int>(i)) != three.report.reseeded.end();
            CHECK(steps[i].reseeded == reseeded);
        }
        CHECK(std::isinf(steps.front().change));
        CHECK(steps.back().components == static_cast<int>(three.means.size()));
    }
}

TEST_CASE("EM: degenerate data gives finite tables or a clear error") {
    // Identical samples: every component collapses onto them; the MAP floor keeps covariances positive.
    Eigen::MatrixXd same = Eigen::MatrixXd::Constant(3, 50, 0.7);
    const GmmFit fit = fit_gmm(same, 4, Covariance::full, 1e-4, 50, 1e-8, 1);
    for (const auto& cov : fit.covariances) CHECK(cov.allFinite());
    ModelData data;
    CHECK_NOTHROW(set_gmm(data, fit.means, fit.covariances, fit.weights, Covariance::full));
    for (float v : data.gmm_factors) CHECK(std::isfinite(v));
    // More components than the data supports: emptied ones are re-seeded, and a
    // component that keeps collapsing is dropped; the objective is monotone
    // between recoveries and the fit ends with finite tables.
    for (const Covariance kind : {Covariance::full, Covariance::diagonal}) {
        Eigen::MatrixXd overlapping = blobs(300, 4);
        overlapping.row(0) *= 0.3;
        const GmmFit recovered = fit_gmm(overlapping, 8, kind, 1e-3, 300, 1e-12, 5);
        CHECK(recovered.means.size() + static_cast<std::size_t>(recovered.report.dropped) == 8);
        for (const auto& cov : recovered.covariances) CHECK(cov.allFinite());
        for (double w : recovered.weights) CHECK(w > 0.0);
        const auto& o = recovered.report.objective;
        const auto& r = recovered.report.reseeded;
        for (std::size_t i = 1; i < o.size(); ++i)
            if (std::find(r.begin(), r.end(), static_cast<int>(i)) == r.end())
                CHECK(o[i] >= o[i - 1] - 1e-9 * std::fabs(o[i - 1]));
        CHECK(r.size() <= 8 * 3);
    }
    // Fewer samples than components, non-finite samples: refused.
    CHECK_THROWS_AS(fit_gmm(Eigen::MatrixXd::Zero(2, 3), 4, Covariance::full, 1e-4, 10, 1e-8, 1),
                    std::invalid_argument);
    Eigen::MatrixXd bad = blobs(10, 1);
    bad(1, 3) = std::nan("");
    CHECK_THROWS_AS(fit_gmm(bad, 2, Covariance::full, 1e-4, 10, 1e-8, 1), std::invalid_argument);
}

TEST_CASE("a PCA wider than the input says how wide it may be") {
    Eigen::MatrixXd samples = Eigen::MatrixXd::Random(9, 40);  // a 3-joint rig's 9 coordinates, 40 poses
    Eigen::VectorXd mean;
    Eigen::MatrixXd axes;
    fit_pca(samples, 9, mean, axes);
    CHECK(axes.rows() == 9);
    CHECK_THROWS_WITH_AS(fit_pca(samples, 24, mean, axes),
                         doctest::Contains("PCA dimension 24 must be between 1 and the input's 9 coordinates"),
                         std::invalid_argument);
    CHECK_THROWS_WITH_AS(fit_pca(samples, 0, mean, axes), doctest::Contains("give --pca 9 or less"),
                         std::invalid_argument);
}

TEST_CASE("the tree splits exactly while the L1 diameter reaches ε") {
    // Four corners of a square of side 1 in 2-D: L1 diameter 2, pairs at 1.
    const std::vector<float> corners = {0, 0, 1, 0, 0, 1, 1, 1};
    CHECK(diameter_reaches(corners, 2, {0, 1, 2, 3}, 2.0, 100));
    CHECK_FALSE(diameter_reaches(corners, 2, {0, 1, 2, 3}, 2.01, 100));
    CHECK(diameter_reaches(corners, 2, {0, 1}, 1.0, 100));
    CHECK_FALSE(diameter_reaches(corners, 2, {0, 1}, 1.01, 100));
    const ClusterTree fine = build_cluster_tree(corners, 2, 0.5, 100, 1);
    CHECK(fine.character_count == 4);
    const ClusterTree coarse = build_cluster_tree(corners, 2, 2.5, 100, 1);
    CHECK(coarse.character_count == 1);
    for (std::size_t node = 0; node < fine.characters.size(); ++node)
        for (int side = 0; side < 2; ++side) {
            const int child = fine.children[2 * node + static_cast<std::size_t>(side)];
            if (child >= 0) CHECK(child > static_cast<int>(node));
        }
}

TEST_CASE("agglomeration merges while ≤ σ, keeps the medoid first, leaves singletons") {
    // Strings 0–2 close together, 3–4 close together, 5 alone.
    std::vector<std::vector<double>> d(6, std::vector<double>(6, 50.0));
    for (int i = 0; i < 6; ++i) d[static_cast<std::size_t>(i)][static_cast<std::size_t>(i)] = 0;
    auto set = [&](int a, int b, double v) {
        d[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] =
            d[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)] = v;
    };
    set(0, 1, 2);
    set(1, 2, 2);
    set(0, 2, 4);
    set(3, 4, 3);
    const auto clusters = agglomerate(d, 5.0);
    REQUIRE(clusters.size() == 3);
    CHECK(clusters[0].front() == 1);  // 1 is at most 2 from the others
    CHECK(clusters[0].size() == 3);
    CHECK(clusters[1].size() == 2);
    CHECK(clusters[2] == std::vector<std::size_t>{5});
    CHECK(agglomerate(d, 1.0).size() == 6);
}

TEST_CASE("pairwise string distances: one direction where both agree, bit for bit with both") {
    std::mt19937 rng(5);
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int trial = 0; trial < 24; ++trial) {
        const int K = uniform(2, 6);
        std::vector<float> w(static_cast<std::size_t>(K * K));
        for (auto& v : w) v = std::uniform_real_distribution<float>(0.0f, 3.0f)(rng);  // rounding-prone values
        if (trial % 2 == 0)
            for (int a = 0; a < K; ++a)
                for (int b = 0; b < a; ++b) w[static_cast<std::size_t>(b * K + a)] = w[static_cast<std::size_t>(a * K + b)];
        ModelView view;
        view.character_count = static_cast<std::uint16_t>(K);
        view.character_distances = w.data();
        std::vector<std::vector<Character>> strings(9);
        for (auto& s : strings) {
            s.resize(static_cast<std::size_t>(uniform(0, 3) == 0 ? 0 : uniform(1, 6)));  // equal lengths are common
            for (auto& c : s) c = static_cast<Character>(uniform(0, K - 1));
        }
        const MatchOptions match{static_cast<MatchVariant>(trial % 3), static_cast<LengthNormalization>((trial / 3) % 3)};
        const auto fast = pairwise_string_distances(view, strings, match, 2);
        std::vector<detail::Cell> workspace(64);
        for (std::size_t a = 0; a < strings.size(); ++a)
            for (std::size_t b = 0; b < strings.size(); ++b) {
                if (a == b) {
                    CHECK(fast[a][b] == 0.0);
                    continue;
                }
                double expected = std::numeric_limits<double>::infinity();
                if (!strings[a].empty() && !strings[b].empty()) {
                    float ab = 0, ba = 0;
                    REQUIRE(string_distance(strings[a].data(), strings[a].size(), strings[b].data(), strings[b].size(),
                                            character_weights(view), match, workspace.data(), &ab) == Status::ok);
                    REQUIRE(string_distance(strings[b].data(), strings[b].size(), strings[a].data(), strings[a].size(),
                                            character_weights(view), match, workspace.data(), &ba) == Status::ok);
                    expected = 0.5 * (static_cast<double>(ab) + static_cast<double>(ba));
                }
                CAPTURE(trial);
                CHECK(fast[a][b] == expected);  // exact
            }
    }
}

TEST_CASE("agglomeration past σ while over a budget: nearest first, down to one cluster") {
    // Points on a line at 0, 1, 3, 7, 15: each gap twice the one before.
    const std::vector<double> at{0, 1, 3, 7, 15};
    std::vector<std::vector<double>> d(5, std::vector<double>(5));
    for (std::size_t a = 0; a < 5; ++a)
        for (std::size_t b = 0; b < 5; ++b) d[a][b] = std::fabs(at[a] - at[b]);
    double last = -1;
    CHECK(agglomerate(d, 0.5, {}, &last).size() == 5);
    CHECK(last == 0.0);
    // At most three clusters: σ = 0.5 merges nothing, the budget merges the two nearest pairs.
    ClusterBudget three;
    three.over = [](const std::vector<std::vector<std::size_t>>& clusters, const std::vector<std::size_t>& medoids) {
        CHECK(medoids.size() == clusters.size());
        return clusters.size() > 3;
    };
    const auto clusters = agglomerate(d, 0.5, three, &last);
    REQUIRE(clusters.size() == 3);
    CHECK(clusters[0].size() == 3);  // 0, 1, 3: merged at 1, then at 2 or 3 from the medoid
    CHECK(clusters[1] == std::vector<std::size_t>{3});
    CHECK(clusters[2] == std::vector<std::size_t>{4});
    CHECK(last > 0.5);
    // A budget nothing satisfies stops at one cluster.
    ClusterBudget never;
    never.over = [](const auto&, const auto&) { return true; };
    const auto one = agglomerate(d, 0.5, never);
    CHECK(one.size() == 1);
    CHECK(one[0].size() == 5);
    // ... or where no pair may merge: here 3 and 4 only with each other.
    never.may_merge = [](const std::vector<std::size_t>& a, const std::vector<std::size_t>& b) {
        return (a.front() >= 3) == (b.front() >= 3);
    };
    const auto two = agglomerate(d, 0.5, never);
    REQUIRE(two.size() == 2);
    CHECK(two[0] == std::vector<std::size_t>{1, 0, 2});  // medoid first: 1 is at most 2 from the others
    CHECK(two[1] == std::vector<std::size_t>{3, 4});
}

TEST_CASE("max_representative_chars bounds the representatives' characters, deterministically") {
    // Performances at three frame rates: some labels get two distinct strings.
    ToyWorld world = make_toy_world();
    auto train = toy_clips(world, 6, 100);
    for (const auto& more : {toy_clips(world, 6, 200, 30.0), toy_clips(world, 6, 300, 90.0)})
        train.insert(train.end(), more.begin(), more.end());
    const auto held_out = toy_clips(world, 5, 9000, 30.0);
    TrainingOptions options = toy_options();
    options.sigma = 0.0;  // merge only equal strings
    options.keep_singletons = true;
    TrainingReport free_report;
    const ModelData free_model = train_model(train, options, &free_report);
    CHECK(free_report.representative_chars == free_model.view().total_representative_chars());
    CHECK(free_report.budget_merge_distance == 0.0);
    REQUIRE(free_report.representatives > static_cast<int>(free_model.label_names.size()));
    // A bound the σ clusters already fit changes nothing.
    options.max_representative_chars = static_cast<int>(free_report.representative_chars);
    CHECK(serialize_model(train_model(train, options, nullptr)) == serialize_model(free_model));
    // A tighter one merges past σ until the medoids fit.
    const std::size_t budget = free_report.representative_chars - 1;
    options.max_representative_chars = static_cast<int>(budget);
    TrainingReport report;
    const ModelData bounded = train_model(train, options, &report);
    CHECK(report.representative_chars <= budget);
    CHECK(report.representative_chars == bounded.view().total_representative_chars());
    CHECK(report.representatives < free_report.representatives);
    CHECK(report.budget_merge_distance > 0.0);
    CHECK(validate_model(bounded.view()) == Status::ok);
    // Past σ only clusters of one label merge: every label keeps a representative.
    for (int count : report.representatives_per_label) CHECK(count >= 1);
    CHECK(clip_accuracy(bounded.view(), held_out) >= 0.9);
    // Deterministic: the same bytes again.
    CHECK(serialize_model(train_model(train, options, nullptr)) == serialize_model(bounded));
    // Below what one representative needs: a clear error.
    options.max_representative_chars = 1;
    CHECK_THROWS_WITH_AS(train_model(train, options, nullptr), doctest::Contains("max-representative-chars 1 is below what one representative per label needs"),
                         std::invalid_argument);
    // The same bound as a share of what σ leaves: the count it stands for is
    // recorded, the medoids fit in it, and a count of its own is the same model.
    options.max_representative_chars = 0;
    options.max_representative_share = 0.8;
    TrainingReport shared;
    const ModelData by_share = train_model(train, options, &shared);
    const auto allowed =
        static_cast<std::size_t>(std::ceil(0.8 * static_cast<double>(free_report.representative_chars)));
    CHECK(shared.representative_budget == allowed);
    CHECK(shared.representative_chars <= allowed);
    CHECK(shared.representatives < free_report.representatives);
    for (int count : shared.representatives_per_label) CHECK(count >= 1);
    CHECK(serialize_model(train_model(train, options, nullptr)) == serialize_model(by_share));
    options.max_representative_share = 0.0;
    options.max_representative_chars = static_cast<int>(allowed);
    CHECK(serialize_model(train_model(train, options, nullptr)) == serialize_model(by_share));
    // With both, the tighter binds.
    options.max_representative_share = 0.8;
    options.max_representative_chars = static_cast<int>(budget);
    CHECK(serialize_model(train_model(train, options, nullptr)) ==
          serialize_model(allowed < budget ? by_share : bounded));
    // A share too small for one representative per label: a clear error that names it.
    options.max_representative_chars = 0;
    options.max_representative_share = 0.01;
    CHECK_THROWS_WITH_AS(train_model(train, options, nullptr), doctest::Contains("max-representative-share 0.01"),
                         std::invalid_argument);
    options.max_representative_share = 1.0;
    CHECK_THROWS_WITH_AS(train_model(train, options, nullptr), doctest::Contains("below 1"), std::invalid_argument);
}

TEST_CASE("a label's bound: the J-best bound keeping enough positives, halfway to the next distance") {
    const float inf = std::numeric_limits<float>::infinity();
    // Negatives far from every positive: all positives kept, the bound halfway to the nearest negative.
    CHECK(choose_label_bound({1, 2, 3}, {10, 11}, 0.95) == 6.5f);
    // Negatives among the positives: keeping 3 of 4 rejects both negatives (J 1.75), keeping 4 only one (1.5).
    CHECK(choose_label_bound({1, 2, 3, 4}, {3.5f, 5}, 0.75) == 3.25f);
    // ... unless the positives to keep forbid it.
    CHECK(choose_label_bound({1, 2, 3, 4}, {3.5f, 5}, 1.0) == 4.5f);
    // Nothing to learn from, or every negative below the positives: no bound.
    CHECK(choose_label_bound({1, 2}, {}, 0.95) == inf);
    CHECK(choose_label_bound({}, {1}, 0.95) == inf);
    CHECK(choose_label_bound({5, 6}, {1, 2}, 0.95) == inf);
    CHECK_THROWS_AS(choose_label_bound({1}, {2}, 0.0), std::invalid_argument);
}

TEST_CASE("synthetic negatives: spliced halves of two labels, each clip faster and slower, seeded") {
    const std::vector<std::vector<Character>> strings{{1, 1, 2, 2}, {3, 3, 4, 4, 5, 5}, {6}};
    const std::vector<LabelId> labels{0, 1, 0};
    const auto negatives = synthetic_negatives(strings, labels, 7);
    REQUIRE(negatives.size() == 2 + 2 * 2);  // the one-character string makes none
    CHECK(negatives[0].string == std::vector<Character>{1, 1, 4, 5, 5});  // string 0's half, string 1's half
    CHECK(negatives[0].own == unknown_label);
    CHECK(negatives[1].string == std::vector<Character>{3, 3, 4, 2, 2});
    CHECK(negatives[2].string == std::vector<Character>{1, 2});  // twice as fast
    CHECK(negatives[2].own == 0);
    CHECK(negatives[3].string == std::vector<Character>{1, 1, 1, 1, 2, 2, 2, 2});  // half as fast
    CHECK(synthetic_negatives(strings, labels, 7)[0].string == negatives[0].string);
    // Rows per character (two floats each here) are cut and repeated with the characters.
    std::vector<std::vector<float>> rows;
    for (const auto& string : strings) {
        rows.emplace_back();
        for (const Character c : string) rows.back().insert(rows.back().end(), {static_cast<float>(c), -1.0f});
    }
    // Several sets of rows (three floats each in the second), each cut as the characters are.
    std::vector<std::vector<float>> wide;
    for (const auto& string : strings) {
        wide.emplace_back();
        for (const Character c : string)
            wide.back().insert(wide.back().end(), {-static_cast<float>(c), 0.5f, static_cast<float>(c) * 2.0f});
    }
    const auto with_rows = synthetic_negatives(strings, labels, 7, {{&rows, 2}, {&wide, 3}});
    REQUIRE(with_rows.size() == negatives.size());
    for (std::size_t k = 0; k < with_rows.size(); ++k) {
        const SyntheticNegative& n = with_rows[k];
        CHECK(n.string == negatives[k].string);  // the same cuts with rows or without
        CHECK(negatives[k].rows.empty());
        REQUIRE(n.rows.size() == 2);
        REQUIRE(n.rows[0].size() == 2 * n.string.size());
        REQUIRE(n.rows[1].size() == 3 * n.string.size());
        for (std::size_t t = 0; t < n.string.size(); ++t) {
            CHECK(n.rows[0][2 * t] == static_cast<float>(n.string[t]));
            CHECK(n.rows[0][2 * t + 1] == -1.0f);
            CHECK(n.rows[1][3 * t] == -static_cast<float>(n.string[t]));
            CHECK(n.rows[1][3 * t + 1] == 0.5f);
            CHECK(n.rows[1][3 * t + 2] == static_cast<float>(n.string[t]) * 2.0f);
        }
    }
    CHECK_THROWS_AS(synthetic_negatives(strings, labels, 7, {{&rows, 3}}), std::invalid_argument);
    CHECK_THROWS_AS(synthetic_negatives(strings, labels, 7, {{nullptr, 2}}), std::invalid_argument);
    rows[1].pop_back();
    CHECK_THROWS_AS(synthetic_negatives(strings, labels, 7, {{&rows, 2}}), std::invalid_argument);
}

TEST_CASE("learned rejection: the toy world's performances kept, what is none of them unknown, deterministic") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 6, 100);
    const auto held_out = toy_clips(world, 5, 9000, 30.0);
    TrainingOptions options = toy_options();
    options.reject = true;
    TrainingReport report;
    const ModelData model = train_model(train, options, &report);
    const ModelView view = model.view();
    REQUIRE(validate_model(view) == Status::ok);
    REQUIRE(view.has_label_bounds == 1);
    REQUIRE(report.label_bounds.size() == view.label_count);
    for (const LabelBoundReport& b : report.label_bounds) {
        CHECK(b.positives > 0);
        CHECK(b.positives_kept >= options.reject_keep);
    }
    CHECK(clip_accuracy(view, held_out) >= 0.9);
    // A performance spliced from two actions' halves is none of them.
    std::size_t rejected = 0, spliced = 0;
    for (std::size_t i = 0; i + 1 < held_out.size(); ++i) {
        if (held_out[i].label == held_out[i + 1].label) continue;
        std::vector<Character> a = clip_string(view, held_out[i].clip), b = clip_string(view, held_out[i + 1].clip);
        a.resize(a.size() / 2);
        a.insert(a.end(), b.begin() + static_cast<long>(b.size() / 2), b.end());
        ++spliced;
        rejected += classify_string(view, a).label == unknown_label;
    }
    REQUIRE(spliced > 0);
    CHECK(rejected > 0);
    // A key-pose held still, unlike any action, must be rejected.
    const std::vector<Character> still(40, view.representative_chars[0]);
    CHECK(classify_string(view, still).label == unknown_label);
    CHECK(serialize_model(train_model(train, options, nullptr)) == serialize_model(model));
    // Without it, nothing is unknown.
    options.reject = false;
    const ModelData plain = train_model(train, options, nullptr);
    CHECK(plain.view().has_label_bounds == 0);
    CHECK(classify_string(plain.view(), still).label != unknown_label);
}

TEST_CASE("training on the toy world recognises held-out performances") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 6, 100);
    const auto held_out = toy_clips(world, 5, 9000, 30.0);
    TrainingReport report;
    ModelData model = train_model(train, toy_options(), &report);
    const ModelView view = model.view();
    CHECK(validate_model(view) == Status::ok);
    CHECK(report.em.converged);
    CHECK(report.characters >= 5);
    for (int count : report.representatives_per_label) CHECK(count >= 1);
    CHECK(clip_accuracy(view, held_out) >= 0.9);
}

TEST_CASE("exemplars: k-means centres per label, their scale measured, deterministic, stored and used") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 6, 100);
    const auto held_out = toy_clips(world, 5, 9000, 30.0);
    TrainingOptions options = toy_pca_only_options();
    options.exemplars = 4;
    options.exemplar_weight = 2.0;
    const ModelData model = train_model(train, options);
    const ModelView view = model.view();
    REQUIRE(validate_model(view) == Status::ok);
    REQUIRE(view.has_exemplars());
    // Every label has far more than four features: four centres each, label by label.
    CHECK(view.exemplar_count == 4u * view.label_count);
    for (std::size_t e = 0; e < view.exemplar_count; ++e) CHECK(view.exemplar_labels[e] == e / 4);
    CHECK(view.exemplar_weight == 2.0f);
    // The scale is the training characters' mean squared distance to their own label's nearest centre.
    double own = 0.0;
    std::size_t n = 0;
    std::vector<float> d(view.label_count);
    for (const LabelledClip& c : train) {
        const EncodedClip encoded = encode_clip(view, c.clip, true);
        const std::size_t label = static_cast<std::size_t>(
            std::find(model.label_names.begin(), model.label_names.end(), c.label) - model.label_names.begin());
        for (std::size_t at = 0; at < encoded.features.size(); at += view.feature_dim, ++n) {
            exemplar_distances(view, &encoded.features[at], d.data());
            own += d[label];
        }
    }
    REQUIRE(n > 0);
    CHECK(view.exemplar_scale > 0.0f);
    CHECK(view.exemplar_scale == doctest::Approx(own / static_cast<double>(n)).epsilon(1e-4));
    // Deterministic, and through the artifact bit for bit.
    CHECK(serialize_model(train_model(train, options)) == serialize_model(model));
    CHECK(serialize_model(parse_model("x.model", serialize_model(model))) == serialize_model(model));
    // Held-out performances: still recognised; the exemplars' penalties reach the kNN.
    CHECK(clip_accuracy(view, held_out) >= 0.9);
    std::size_t changed = 0;
    for (const LabelledClip& c : held_out) {
        const EncodedClip encoded = encode_clip(view, c.clip, true);
        const std::vector<float> sums = exemplar_sums(view, encoded.features);
        const Classification with = classify_string(view, encoded.string, {}, sums.data());
        CHECK(with.label == classify_clip(view, c.clip).label);
        const Classification without = classify_string(view, encoded.string);
        // The winner's distance grew by exactly its exemplar penalty.
        std::vector<float> penalties(view.label_count);
        exemplar_penalties(view, sums.data(), encoded.string.size(), penalties.data());
        if (with.label == without.label && with.representative == without.representative)
            CHECK(with.distance == doctest::Approx(without.distance + penalties[with.label]));
        changed += *std::max_element(penalties.begin(), penalties.end()) > 0.0f;
    }
    CHECK(changed == held_out.size());  // every clip's other labels lie further from their exemplars
    // No weight or no centres: none.
    options.exemplar_weight = 0.0;
    CHECK_FALSE(train_model(train, options).view().has_exemplars());
    // Rejection bounds learned with the exemplars: the samples' exemplar rows are
    // spliced and warped with their characters, measured with centres fitted
    // without their subject. The positives are kept, held-out clips still
    // recognised, spliced performances (features spliced too) partly rejected.
    options.exemplar_weight = 2.0;
    options.reject = true;
    TrainingReport report;
    const ModelData rejecting = train_model(train, options, &report);
    const ModelView rview = rejecting.view();
    REQUIRE(validate_model(rview) == Status::ok);
    REQUIRE(rview.has_exemplars());
    REQUIRE(rview.has_label_bounds == 1);
    for (const LabelBoundReport& b : report.label_bounds) {
        CHECK(b.positives > 0);
        CHECK(b.positives_kept >= options.reject_keep);
    }
    CHECK(clip_accuracy(rview, held_out) >= 0.9);
    std::size_t rejected = 0, spliced = 0;
    for (std::size_t i = 0; i + 1 < held_out.size(); ++i) {
        if (held_out[i].label == held_out[i + 1].label) continue;
        EncodedClip a = encode_clip(rview, held_out[i].clip, true);
        const EncodedClip b = encode_clip(rview, held_out[i + 1].clip, true);
        const std::size_t first = a.string.size() / 2, second = b.string.size() / 2, dim = rview.feature_dim;
        a.string.resize(first);
        a.string.insert(a.string.end(), b.string.begin() + static_cast<long>(second), b.string.end());
        a.features.resize(first * dim);
        a.features.insert(a.features.end(), b.features.begin() + static_cast<long>(second * dim), b.features.end());
        ++spliced;
        const std::vector<float> sums = exemplar_sums(rview, a.features);
        rejected += classify_string(rview, a.string, {}, sums.data()).label == unknown_label;
    }
    REQUIRE(spliced > 0);
    CHECK(rejected > 0);
    CHECK(serialize_model(train_model(train, options)) == serialize_model(rejecting));
}

TEST_CASE("exemplars: a label with fewer features than centres keeps every feature as a centre") {
    ModelData m;
    m.feature_dim = 2;
    const std::vector<std::string> names{"a", "b"};
    m.label_names.assign(names.begin(), names.end());
    // Label a: three features; label b: one feature twice (both characters on it).
    const std::vector<std::vector<float>> features{{0, 0, 1, 0}, {5, 5, 5, 5}, {0, 1}};
    const std::vector<LabelId> labels{0, 1, 0};
    set_exemplars(m, features, labels, 8, 0, 1.0, 1);
    CHECK(m.exemplar_labels == std::vector<LabelId>{0, 0, 0, 1, 1});
    CHECK(m.exemplars == std::vector<float>{0, 0, 1, 0, 0, 1, 5, 5, 5, 5});
    // Every feature is a centre of its own label, so the scale is the nearest other label's mean distance.
    const double other = (50.0 + 41.0 + 41.0 + 41.0 + 41.0) / 5.0;  // (5,5)'s nearest of a is (1,0)
    CHECK(m.exemplar_scale == doctest::Approx(other));
    // Features of no action (stretches of recordings): centres of their own, last,
    // and no part in the scale.
    std::vector<std::vector<float>> with_none = features;
    with_none.push_back({9, 9, 8, 8});
    std::vector<LabelId> none_labels = labels;
    none_labels.push_back(unknown_label);
    set_exemplars(m, with_none, none_labels, 8, 0, 1.0, 1);
    CHECK(m.exemplar_labels == std::vector<LabelId>{0, 0, 0, 1, 1, unknown_label, unknown_label});
    CHECK(m.exemplars == std::vector<float>{0, 0, 1, 0, 0, 1, 5, 5, 5, 5, 9, 9, 8, 8});
    CHECK(m.exemplar_scale == doctest::Approx(other));
    CHECK(m.view().has_no_action_exemplars());
    // Only no action's features: nothing to classify clips with.
    CHECK_THROWS_AS(set_exemplars(m, {{9, 9}}, {unknown_label}, 8, 0, 1.0, 1), std::invalid_argument);
    set_exemplars(m, features, labels, 0, 0, 1.0, 1);
    CHECK(m.exemplar_labels.empty());
    CHECK(m.exemplar_weight == 0.0f);
    // The first coordinate only: each centre keeps one, and the scale is measured on it.
    set_exemplars(m, features, labels, 8, 1, 1.0, 1);
    CHECK(m.exemplar_dim == 1);
    CHECK(m.view().exemplar_dims() == 1);
    CHECK(m.exemplars == std::vector<float>{0, 1, 0, 5, 5});
    // Every feature is its own centre again, so the nearest other label's: 25, 16, 25 for a; 16, 16 for b.
    CHECK(m.exemplar_scale == doctest::Approx((25.0 + 16.0 + 25.0 + 16.0 + 16.0) / 5.0));
    // All of them: stored as 0 (every coordinate), so older models read the same way.
    set_exemplars(m, features, labels, 8, 2, 1.0, 1);
    CHECK(m.exemplar_dim == 0);
    CHECK_THROWS_AS(set_exemplars(m, features, labels, 8, 3, 1.0, 1), std::invalid_argument);
}

TEST_CASE("a model without a GMM (PCA-only characters) trains, validates, round-trips and generates a header") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 6, 100);
    const auto held_out = toy_clips(world, 5, 9000, 30.0);
    TrainingOptions options = toy_pca_only_options();
    TrainingReport report;
    ModelData model = train_model(train, options, &report);
    const ModelView view = model.view();
    CHECK(validate_model(view) == Status::ok);
    CHECK_FALSE(view.has_gmm());
    CHECK(view.tree_dim() == 6);
    CHECK(view.gmm_means == nullptr);
    CHECK(report.em.objective.empty());  // no EM ran
    CHECK(report.characters >= 5);
    // The scaled projection keeps every training feature within L1 distance 1 of the mean pose.
    CHECK(*std::max_element(model.character_distances.begin(), model.character_distances.end()) <= 2.0f);
    CHECK(clip_accuracy(view, held_out) >= 0.9);
    // The annotator runs it, with no storage for a posterior it does not compute.
    Stateful<Annotator> annotator;
    REQUIRE(annotator.init(view, annotator_config(view)) == Status::ok);
    const std::string text = serialize_model(model);
    ModelData loaded = parse_model("m.model", text);
    CHECK(serialize_model(loaded) == text);
    const std::string header = generate_header(model, artifact_checksum(text), "pca_only", "m.model");
    CHECK(header.find("m.gmm_means = nullptr;") != std::string::npos);
    CHECK(header.find("kGmmMeans") == std::string::npos);
    CHECK(header.find("feature_dim = 6;") != std::string::npos);
    CHECK(header.find("m.component_count = 0;") != std::string::npos);  // and no state for a posterior
    // The characters' votes: for every label a distribution over the K characters.
    REQUIRE(view.has_votes());
    CHECK(view.vote_weight == 1.0f);
    for (std::size_t l = 0; l < view.label_count; ++l) {
        double total = 0;
        for (std::size_t c = 0; c < view.character_count; ++c)
            total += std::exp(static_cast<double>(view.character_votes[l * view.character_count + c]));
        CHECK(total == doctest::Approx(1.0).epsilon(1e-5));
    }
    CHECK(header.find("kCharacterVotes") != std::string::npos);
    // Weight 0: no table, DTW alone.
    TrainingOptions no_votes = options;
    no_votes.vote_weight = 0;
    const ModelData plain = train_model(train, no_votes);
    CHECK_FALSE(plain.view().has_votes());
    CHECK(plain.character_votes.empty());
    // Without a projection there is nothing to scale: refused with a reason.
    options.pca_dim = 0;
    CHECK_THROWS_WITH_AS(train_model(train, options), doctest::Contains("needs a projection"), std::invalid_argument);
}

TEST_CASE("the same inputs and seed give byte-identical artifacts and headers") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 4, 200);
    TrainingOptions options = toy_options();
    options.pca_dim = 6;
    ModelData a = train_model(train, options);
    ModelData b = train_model(train, options);
    const std::string text_a = serialize_model(a), text_b = serialize_model(b);
    CHECK(text_a == text_b);
    CHECK(generate_header(a, artifact_checksum(text_a), "m", "a.model") ==
          generate_header(b, artifact_checksum(text_b), "m", "a.model"));
    options.seed = 2;
    ModelData c = train_model(train, options);
    CHECK(serialize_model(c) != text_a);  // the seed matters, so the comparison above can fail
}

TEST_CASE("artifacts round-trip exactly and refuse corruption") {
    ToyWorld world = make_toy_world();
    std::string text = serialize_model(world.model);
    ModelData loaded = parse_model("m.model", text);
    CHECK(serialize_model(loaded) == text);
    CHECK(loaded.gmm_factors == world.model.gmm_factors);  // every float, bit for bit
    CHECK(loaded.label_names == world.model.label_names);

    auto refused = [&](const std::string& bad, const std::string& fragment) {
        try {
            parse_model("m.model", bad);
            FAIL("accepted a bad artifact; expected '" << fragment << "'");
        } catch (const ReadError& error) {
            const std::string message = error.what();
            CAPTURE(message);
            CHECK(message.find(fragment) != std::string::npos);
        }
    };
    std::string flipped = text;
    flipped[flipped.size() / 2] = flipped[flipped.size() / 2] == '1' ? '2' : '1';
    refused(flipped, "checksum mismatch");
    refused(text.substr(0, text.size() / 2), "checksum mismatch");
    refused(text.substr(0, 30), "expected 'checksum fnv1a64");
    refused("", "empty file");
    refused("actionstring-model 99\n", "version 99 is not supported");
    refused("something else\n", "not an actionstring model");
    // A consistent checksum over inconsistent tables: the runtime's validation refuses it.
    world.model.representative_labels[0] = 77;
    const std::vector<std::string> first_label{world.model.label_names[0]};
    world.model.label_names.assign(first_label.begin(), first_label.end());
    refused(serialize_model(world.model), "invalid model: representative_labels: not a label of the model");
}

namespace {

// A model's artifact as an earlier version wrote it: the version line, and
// none of the fields added since (version 6: the exemplars; 7: the
// acceleration's weight; 8: the events' shortest action; 9: the exemplars'
// dimension; 10: the clip descriptor; 11: the label lead; 12: the motion
// directions; 13: early settling; 14: the window's directions).
std::string older_artifact(const ModelData& model, int version) {
    std::string body;
    const std::string fields = serialize_fields(model);
    for (std::size_t at = 0; at < fields.size();) {
        const std::size_t end = fields.find('\n', at) + 1;
        const std::string line = fields.substr(at, end - at);
        const bool added =
            (version < 6 && line.find("exemplar") != std::string::npos) ||
            (version < 7 && line.find("acceleration_weight") != std::string::npos) ||
            (version < 8 && line.find("min_action_us") != std::string::npos) ||
            (version < 9 && line.find("exemplar_dim ") == 0) || (version < 10 && line.find("descriptor") == 0) ||
            (version < 11 && line.find("label_lead_us") == 0) || (version < 12 && line.find("direction") == 0) ||
            (version < 13 && line.find("settle_stable_us") == 0) ||
            (version < 14 && (line.find("window_direction") == 0 || line.find("segment_direction_weight") == 0));
        if (!added) body += line;
        at = end;
    }
    char checksum[24];
    std::snprintf(checksum, sizeof checksum, "%016llx", static_cast<unsigned long long>(fnv1a64(body)));
    return "actionstring-model " + std::to_string(version) + "\nchecksum fnv1a64 " + checksum + "\n" + body;
}

}  // namespace

TEST_CASE(
    "version-5 to 13 artifacts (before the exemplars, the acceleration, the shortest action, the exemplars' "
    "dimension, the clip descriptor, the label lead, the motion directions, early settling, the window's "
    "directions) are read") {
    const ToyWorld world = make_toy_world();
    REQUIRE_FALSE(world.model.view().has_exemplars());
    REQUIRE_FALSE(world.model.view().has_acceleration());
    REQUIRE(world.model.min_action_us == 250000u);  // what a model without the field has
    for (const int version : {5, 6, 7, 8, 9, 10, 11, 12, 13}) {
        CAPTURE(version);
        const std::string old = older_artifact(world.model, version);
        CHECK(serialize_model(parse_model("old.model", old)) == serialize_model(world.model));
        // The same lines under the current version lack fields: refused, with the
        // line (the first field missing from them).
        std::string current = old;
        current.replace(0, current.find('\n'), "actionstring-model " + std::to_string(artifact_version));
        const char* const missing = version < 7    ? "expected 'acceleration_weight'"
                                    : version < 9  ? "expected 'exemplar_dim'"
                                    : version < 10 ? "expected 'descriptor_weight'"
                                    : version < 12 ? "expected 'direction_weight'"         // before label_lead_us
                                                   : "expected 'window_direction_chars'";  // before settle_stable_us
        CHECK_THROWS_WITH_AS(parse_model("new.model", current), doctest::Contains(missing), ReadError);
    }
    // A version-7 model's events keep the runtime's default shortest action.
    ModelData shorter = parse_model("copy.model", serialize_model(world.model));
    shorter.min_action_us = 500000;
    CHECK(parse_model("v7.model", older_artifact(shorter, 7)).min_action_us == 250000u);
    CHECK(parse_model("v8.model", older_artifact(shorter, 8)).min_action_us == 500000u);
    // A version-10 model's labels apply at their characters' ticks (no lead).
    shorter.label_lead_us = 200000;
    CHECK(parse_model("v10.model", older_artifact(shorter, 10)).label_lead_us == 0u);
    CHECK(parse_model("v11.model", older_artifact(shorter, 11)).label_lead_us == 200000u);
    // A version-12 model settles by the delay alone.
    shorter.settle_stable_us = 1000000;
    CHECK(parse_model("v12.model", older_artifact(shorter, 12)).settle_stable_us == 0u);
    CHECK(parse_model("v13.model", older_artifact(shorter, 13)).settle_stable_us == 1000000u);
    // A version-13 model has no window of directions, and its segmenter does not weigh one.
    shorter.segment_direction_weight = 0.5f;
    CHECK(parse_model("v13.model", older_artifact(shorter, 13)).segment_direction_weight == 0.0f);
    CHECK(parse_model("v14.model", serialize_model(shorter)).segment_direction_weight == 0.5f);
    // A version-8 model's exemplars keep every coordinate of the feature.
    TrainingOptions options = toy_pca_only_options();
    options.exemplars = 3;
    options.exemplar_weight = 1.0;
    const ModelData with_exemplars = train_model(toy_clips(make_toy_world(), 2, 7), options);
    REQUIRE(with_exemplars.exemplar_dim == 0);
    const ModelData read = parse_model("v8.model", older_artifact(with_exemplars, 8));
    CHECK(read.exemplar_dim == 0);
    CHECK(serialize_model(read) == serialize_model(with_exemplars));
}

TEST_CASE("a version-4 artifact (factors component by component) is read and reordered") {
    const ToyWorld world = make_toy_world();
    const ModelView view = world.model.view();
    REQUIRE(view.component_count == 6);  // a block of four and a short one of two: the order matters
    ModelData old = parse_model("copy.model", serialize_model(world.model));  // a copy
    const std::size_t size = view.factor_size();
    for (std::size_t j = 0; j < view.component_count; ++j)
        for (std::size_t k = 0; k < size; ++k)
            old.gmm_factors[j * size + k] = world.model.gmm_factors[view.gmm_factor_index(j, k)];
    REQUIRE(old.gmm_factors != world.model.gmm_factors);
    const ModelData loaded = parse_model("old.model", older_artifact(old, 4));
    CHECK(loaded.gmm_factors == world.model.gmm_factors);
    CHECK(serialize_model(loaded) == serialize_model(world.model));
    // Read as the current version, the same body is another (wrong) model: the version line matters.
    CHECK(parse_model("new.model", serialize_model(old)).gmm_factors != world.model.gmm_factors);
}

TEST_CASE("generated headers carry the banner, the checksum and exact literals") {
    ToyWorld world = make_toy_world();
    const std::string text = serialize_model(world.model);
    const std::string header = generate_header(world.model, artifact_checksum(text), "toy", "toy.model");
    CHECK(header.rfind("// DO NOT EDIT.", 0) == 0);
    CHECK(header.find(artifact_checksum(text)) != std::string::npos);
    CHECK(header.find("inline constexpr ::actionstring::ModelView kModel") != std::string::npos);
    CHECK(header.find("inline constexpr std::size_t kAnnotatorBytes =") != std::string::npos);
    CHECK(header.find("inline constexpr std::size_t kAnnotatorWithWindowsBytes =") != std::string::npos);
    CHECK(header.find("m.joint_count = 5;") != std::string::npos);
    CHECK(header.find("m.feature_dim = 12;") != std::string::npos);
    CHECK(header.find("m.component_count = 6;") != std::string::npos);
    char literal[48];
    std::snprintf(literal, sizeof literal, "%af", static_cast<double>(world.model.gmm_means[0]));
    CHECK(header.find(literal) != std::string::npos);
}

TEST_CASE("EM restarts run in parallel yet give identical models, keeping the best objective") {
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 3, 400);
    TrainingOptions options = toy_options();
    options.em_restarts = 3;
    TrainingReport first, second;
    ModelData a = train_model(train, options, &first);
    ModelData b = train_model(train, options, &second);
    CHECK(serialize_model(a) == serialize_model(b));
    REQUIRE(first.em_restart_objectives.size() == 3);
    const auto best = std::max_element(first.em_restart_objectives.begin(), first.em_restart_objectives.end());
    CHECK(first.em_restart_chosen == static_cast<int>(best - first.em_restart_objectives.begin()));
    CHECK(first.em_restart_objectives == second.em_restart_objectives);
}

TEST_CASE("'no action' votes: learned from the unlabelled stretches of recordings") {
    // A 10 s recording at 10 Hz with two labelled intervals.
    LabelledRecording recording;
    recording.subject = "s9";
    recording.clip.joint_names = {"a"};
    for (int f = 0; f < 100; ++f) {
        recording.clip.times.push_back(f * 0.1);
        recording.clip.positions.insert(recording.clip.positions.end(), {static_cast<float>(f), 0.0f, 0.0f});
    }
    recording.intervals = {{"wave", 2.0, 4.0}, {"clap", 6.0, 6.5}};
    const std::vector<LabelledClip> long_enough = unlabelled_stretches({recording}, 1.0);
    REQUIRE(long_enough.size() == 3);  // 0–1.9 s, 4.1–5.9 s, 6.6–9.9 s
    CHECK(long_enough[0].clip.frame_count() == 20);
    CHECK(long_enough[1].clip.times.front() == doctest::Approx(4.1));
    CHECK(long_enough[2].clip.frame_count() == 34);
    CHECK(long_enough[2].clip.positions.front() == 66.0f);
    CHECK(long_enough[2].subject == "s9");
    CHECK(long_enough[2].label.empty());
    CHECK(unlabelled_stretches({recording}, 2.0).size() == 1);

    // Training with stretches of no action stores log P(c | no action), a distribution.
    ToyWorld world = make_toy_world();
    const auto train = toy_clips(world, 4, 100);
    TrainingOptions options = toy_pca_only_options();
    const std::vector<LabelledClip> stretches(train.begin(), train.begin() + 3);
    TrainingReport report;
    const ModelData model = train_model(train, options, &report, &stretches);
    const ModelView view = model.view();
    CHECK(validate_model(view) == Status::ok);
    CHECK(report.no_action_stretches == 3);
    REQUIRE(view.has_no_action_votes == 1);
    double total = 0;
    for (std::size_t c = 0; c < view.character_count; ++c) total += std::exp(static_cast<double>(view.no_action_votes[c]));
    CHECK(total == doctest::Approx(1.0).epsilon(1e-5));
    // Without votes there is nothing to learn them for.
    options.vote_weight = 0;
    CHECK(train_model(train, options, nullptr, &stretches).has_no_action_votes == 0);
    // With exemplars, the stretches get centres of their own, after every label's
    // (unless told not to), and the artifact keeps them.
    options.exemplars = 4;
    options.exemplar_weight = 1.0;
    const ModelData with_none = train_model(train, options, nullptr, &stretches);
    CHECK(validate_model(with_none.view()) == Status::ok);
    REQUIRE(with_none.view().has_no_action_exemplars());
    CHECK(std::count(with_none.exemplar_labels.begin(), with_none.exemplar_labels.end(), unknown_label) == 4);
    CHECK(with_none.exemplar_labels.size() == 4 * with_none.label_names.size() + 4);
    CHECK(serialize_model(parse_model("x.model", serialize_model(with_none))) == serialize_model(with_none));
    options.no_action_exemplars = false;
    const ModelData without = train_model(train, options, nullptr, &stretches);
    CHECK_FALSE(without.view().has_no_action_exemplars());
    // The labels' centres and their scale do not depend on no action's.
    CHECK(without.exemplar_scale == with_none.exemplar_scale);
    CHECK(std::equal(without.exemplars.begin(), without.exemplars.end(), with_none.exemplars.begin()));
    // Centres of the features' first coordinates only: fewer floats, the same
    // validation, and the artifact and the header keep the dimension.
    options.exemplar_dims = 2;
    const ModelData leading = train_model(train, options, nullptr, &stretches);
    const ModelView leading_view = leading.view();
    CHECK(validate_model(leading_view) == Status::ok);
    CHECK(leading.exemplar_dim == 2);
    CHECK(leading.exemplars.size() == leading.exemplar_labels.size() * 2);
    const std::string text = serialize_model(leading);
    CHECK(serialize_model(parse_model("x.model", text)) == text);
    CHECK(generate_header(leading, artifact_checksum(text), "leading", "x.model").find("m.exemplar_dim = 2;") !=
          std::string::npos);
    // A view claiming more coordinates than the feature has is refused.
    ModelView wide = leading_view;
    wide.exemplar_dim = static_cast<std::uint16_t>(wide.feature_dim + 1);
    CHECK(validate_model(wide) == Status::invalid_model);
    // Clip classification and the annotator run on it.
    Stateful<Annotator> annotator;
    CHECK(annotator.init(leading_view, annotator_config(leading_view)) == Status::ok);
}

TEST_CASE("clips of a tilted sensor, turned upright as read, train and encode as the upright ones") {
    ToyWorld world = make_toy_world();
    // Clips as a sensor pitched 25° and rolled 10° records them, and its up direction.
    const Eigen::Matrix3f tilt =
        (Eigen::AngleAxisf(0.436f, Eigen::Vector3f::UnitX()) * Eigen::AngleAxisf(0.175f, Eigen::Vector3f::UnitZ()))
            .toRotationMatrix();
    const Eigen::Vector3f up = tilt * Eigen::Vector3f::UnitY();
    auto tilted = [&](std::vector<LabelledClip> clips) {
        for (LabelledClip& c : clips)
            for (std::size_t f = 0; f < c.clip.frame_count(); ++f)
                for (std::size_t j = 0; j < c.clip.joint_count(); ++j) {
                    Eigen::Map<Eigen::Vector3f> p(c.clip.frame(f) + 3 * j);
                    p = tilt * Eigen::Vector3f(p);
                }
        return clips;
    };
    auto turned = [&](std::vector<LabelledClip> clips) {
        for (LabelledClip& c : clips) turn_upright(c.clip, up.data());
        return clips;
    };
    const std::vector<LabelledClip> upright = toy_clips(world, 3, 4100), held_out = toy_clips(world, 3, 4200);
    const TrainingOptions options = toy_options();
    const ModelData reference = train_model(upright, options);
    const ModelData from_turned = train_model(turned(tilted(upright)), options);
    const std::vector<LabelledClip> seen_tilted = tilted(held_out), seen_turned = turned(seen_tilted);
    // Each character of the held-out clips: the upright model on the upright clips against (a) the
    // model trained on turned clips, (b) the upright model on the tilted clips turned back, and (c)
    // on them left tilted. Turned back, they agree up to rounding in the last bits; tilted, not.
    std::size_t total = 0, same_model = 0, same_turned = 0, same_tilted = 0;
    for (std::size_t k = 0; k < held_out.size(); ++k) {
        const std::vector<Character> a = encode_clip(reference.view(), held_out[k].clip, false).string;
        const std::vector<Character> b = encode_clip(from_turned.view(), held_out[k].clip, false).string;
        const std::vector<Character> c = encode_clip(reference.view(), seen_turned[k].clip, false).string;
        const std::vector<Character> d = encode_clip(reference.view(), seen_tilted[k].clip, false).string;
        REQUIRE(b.size() == a.size());
        REQUIRE(c.size() == a.size());
        REQUIRE(d.size() == a.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            same_model += a[i] == b[i];
            same_turned += a[i] == c[i];
            same_tilted += a[i] == d[i];
        }
        total += a.size();
        CHECK(classify_clip(reference.view(), seen_turned[k].clip).label ==
              classify_clip(reference.view(), held_out[k].clip).label);
    }
    REQUIRE(total > 100);
    CHECK(static_cast<double>(same_model) / static_cast<double>(total) > 0.99);
    CHECK(static_cast<double>(same_turned) / static_cast<double>(total) > 0.99);
    CHECK(static_cast<double>(same_tilted) / static_cast<double>(total) < 0.9);
}
