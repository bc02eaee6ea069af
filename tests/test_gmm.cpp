// GMM posterior against an independent double-precision computation.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "actionstring/gmm.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/projection.hpp"
#include "model/model_data.hpp"

using namespace actionstring;

namespace {


struct RandomGmm {
    std::vector<Eigen::VectorXd> means;
    std::vector<Eigen::MatrixXd> covariances;
    std::vector<double> weights;
    host::ModelData data;
};

RandomGmm make_gmm(std::mt19937& rng, Eigen::Index d, int J, Covariance kind) {
    RandomGmm g;
    std::normal_distribution<double> normal(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.2, 1.0);
    double total = 0;
    for (int j = 0; j < J; ++j) {
        Eigen::VectorXd mean(d);
        for (Eigen::Index i = 0; i < d; ++i) mean[i] = 0.5 * normal(rng);
        Eigen::MatrixXd a(d, d);
        for (Eigen::Index i = 0; i < a.size(); ++i) a(i) = 0.3 * normal(rng);
        Eigen::MatrixXd cov = a * a.transpose() + 0.05 * Eigen::MatrixXd::Identity(d, d);
        if (kind == Covariance::diagonal) cov = Eigen::MatrixXd(cov.diagonal().asDiagonal());
        g.means.push_back(mean);
        g.covariances.push_back(cov);
        g.weights.push_back(uniform(rng));
        total += g.weights.back();
    }
    for (auto& w : g.weights) w /= total;
    host::set_gmm(g.data, g.means, g.covariances, g.weights, kind);
    return g;
}

// Posteriors from the textbook densities: explicit inverse and determinant (LU).
std::vector<double> direct_posterior(const RandomGmm& g, const Eigen::VectorXd& x) {
    const double pi = 3.14159265358979323846;
    std::vector<double> p;
    double total = 0;
    for (std::size_t j = 0; j < g.means.size(); ++j) {
        const Eigen::FullPivLU<Eigen::MatrixXd> lu(g.covariances[j]);
        const Eigen::VectorXd diff = x - g.means[j];
        const double q = diff.dot(lu.inverse() * diff);
        const double density =
            std::exp(-0.5 * q) / std::sqrt(std::pow(2 * pi, static_cast<double>(x.size())) * lu.determinant());
        p.push_back(g.weights[j] * density);
        total += p.back();
    }
    for (auto& v : p) v /= total;
    return p;
}

ModelView gmm_view(host::ModelData& data) {
    ModelView v = data.view();
    return v;
}

}  // namespace

TEST_CASE("posteriors match direct densities in double precision") {
    std::mt19937 rng(11);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (const Covariance kind : {Covariance::full, Covariance::diagonal}) {
        for (int trial = 0; trial < 40; ++trial) {
            const Eigen::Index d = 1 + trial % 12;
            const int J = 1 + trial % 7;
            RandomGmm g = make_gmm(rng, d, J, kind);
            const ModelView view = gmm_view(g.data);
            for (int sample = 0; sample < 20; ++sample) {
                // Near a random component, where double densities do not underflow.
                const auto& centre = g.means[static_cast<std::size_t>(sample % J)];
                Eigen::VectorXd x = centre;
                for (Eigen::Index i = 0; i < d; ++i) x[i] += 0.3 * normal(rng);
                const std::vector<double> expected = direct_posterior(g, x);
                std::vector<float> feature(static_cast<std::size_t>(d)), posterior(static_cast<std::size_t>(J)),
                    scratch(gmm_scratch_floats(view));
                for (Eigen::Index i = 0; i < d; ++i) feature[static_cast<std::size_t>(i)] = static_cast<float>(x[i]);
                float log_likelihood = 0;
                REQUIRE(gmm_posterior(view, feature.data(), posterior.data(), scratch.data(), &log_likelihood) ==
                        Status::ok);
                double sum = 0;
                for (int j = 0; j < J; ++j) {
                    CHECK(static_cast<double>(posterior[static_cast<std::size_t>(j)]) ==
                          doctest::Approx(expected[static_cast<std::size_t>(j)]).epsilon(2e-3).scale(1.0));
                    sum += static_cast<double>(posterior[static_cast<std::size_t>(j)]);
                }
                CHECK(sum == doctest::Approx(1.0).epsilon(1e-5));
                CHECK(std::isfinite(log_likelihood));
            }
        }
    }
}

TEST_CASE("far-away poses still give a finite posterior that sums to one") {
    std::mt19937 rng(12);
    RandomGmm g = make_gmm(rng, 6, 5, Covariance::full);
    const ModelView view = gmm_view(g.data);
    for (const float far : {50.0f, 1.0e3f, 2.0e4f, -2.0e4f}) {
        std::vector<float> feature(6, far), posterior(5), scratch(gmm_scratch_floats(view));
        feature[2] = -far;
        REQUIRE(gmm_posterior(view, feature.data(), posterior.data(), scratch.data()) == Status::ok);
        float sum = 0, peak = 0;
        for (float p : posterior) {
            CHECK(std::isfinite(p));
            CHECK(p >= 0.0f);
            sum += p;
            peak = std::max(peak, p);
        }
        CHECK(sum == doctest::Approx(1.0f).epsilon(1e-5));
        CHECK(peak > 0.2f);  // never all zero: the likeliest component takes the mass
    }
    CHECK(gmm_is_overflow_safe(view, max_pose_coordinate));
}

TEST_CASE("a model that could overflow float is detected") {
    std::mt19937 rng(13);
    RandomGmm g = make_gmm(rng, 4, 2, Covariance::diagonal);
    g.data.gmm_factors[0] = 1.0e16f;  // a variance of 1e-32 m²
    const ModelView view = gmm_view(g.data);
    CHECK_FALSE(gmm_is_overflow_safe(view, max_pose_coordinate));
}

TEST_CASE("set_gmm refuses covariances that are not positive definite") {
    host::ModelData data;
    std::vector<Eigen::VectorXd> means{Eigen::VectorXd::Zero(2)};
    std::vector<Eigen::MatrixXd> covs{Eigen::MatrixXd::Zero(2, 2)};
    CHECK_THROWS_AS(host::set_gmm(data, means, covs, {1.0}, Covariance::full), std::invalid_argument);
    covs[0] << 1.0, 2.0, 2.0, 1.0;  // indefinite
    CHECK_THROWS_AS(host::set_gmm(data, means, covs, {1.0}, Covariance::full), std::invalid_argument);
    covs[0] << 1.0, 0.5, 0.4, 1.0;  // not symmetric
    CHECK_THROWS_AS(host::set_gmm(data, means, covs, {1.0}, Covariance::full), std::invalid_argument);
    covs[0] = Eigen::MatrixXd::Identity(2, 2);
    CHECK_THROWS_AS(host::set_gmm(data, means, covs, {0.0}, Covariance::full), std::invalid_argument);
    CHECK_NOTHROW(host::set_gmm(data, means, covs, {1.0}, Covariance::full));
}

TEST_CASE("projection computes P (x - m) in the model's layout") {
    host::ModelData data;
    data.pose_joints = {0, 1};  // D = 6
    data.feature_dim = 2;
    data.projection_mean = {1, 2, 3, 4, 5, 6};
    // P = [[1, 0, 0, 0, 0, 0], [0.5, 0, 0, 0, 0, -2]], stored column by column.
    data.projection_matrix = {1, 0.5f, 0, 0, 0, 0, 0, 0, 0, 0, 0, -2};
    const ModelView view = data.view();
    const float pose[6] = {2, 2, 3, 4, 5, 10};
    float feature[2] = {};
    REQUIRE(project_pose(view, pose, feature) == Status::ok);
    CHECK(feature[0] == 1.0f);
    CHECK(feature[1] == doctest::Approx(0.5 * 1 - 2 * 4));
}

namespace {
// Distance in units in the last place between a float and the exactly rounded
// value of a double, counted on the float grid.
double ulp_error(float approx, double exact) {
    const float rounded = static_cast<float>(exact);
    const float next = std::nextafter(rounded, std::numeric_limits<float>::infinity());
    const double ulp = static_cast<double>(next) - static_cast<double>(rounded);
    return std::fabs(static_cast<double>(approx) - exact) / ulp;
}
}  // namespace

TEST_CASE("the portable exp is within 2 ulp of exp on the runtime's range") {
    double worst = 0.0;
    // Posterior terms are exp(log_joint - peak) ≤ 1; the sweep covers both signs.
    for (int i = 0; i <= 400000; ++i) {
        const float x = -87.0f + 175.0f * static_cast<float>(i) / 400000.0f;
        const double exact = std::exp(static_cast<double>(x));
        if (exact < 1.2e-38) continue;  // below FLT_MIN the runtime flushes to zero
        worst = std::max(worst, ulp_error(detail::exp_portable(x), exact));
    }
    CHECK(worst <= 2.0);
    CHECK(detail::exp_portable(0.0f) == 1.0f);
    CHECK(detail::exp_portable(-1000.0f) == 0.0f);
    CHECK(detail::exp_portable(1000.0f) == std::numeric_limits<float>::infinity());
    CHECK(detail::exp_portable(-std::numeric_limits<float>::infinity()) == 0.0f);
    CHECK(detail::is_nan(detail::exp_portable(std::numeric_limits<float>::quiet_NaN())));
    CHECK(detail::is_finite(detail::exp_portable(88.7f)));
}

TEST_CASE("the portable log is accurate from subnormals to the largest float") {
    double worst_absolute = 0.0, worst_ulp_near_one = 0.0;
    for (int i = 0; i <= 400000; ++i) {
        // Log-spaced over the whole positive range, subnormals included.
        const double x = std::exp(-103.0 + 191.0 * i / 400000.0);
        const float xf = static_cast<float>(x);
        if (!(xf > 0.0f) || !std::isfinite(xf)) continue;
        const double exact = std::log(static_cast<double>(xf));
        const double err = std::fabs(static_cast<double>(detail::log_portable(xf)) - exact);
        // Near 1 the result is small: judge it in ulp there, absolutely elsewhere.
        if (std::fabs(exact) < 0.5)
            worst_ulp_near_one = std::max(worst_ulp_near_one, ulp_error(detail::log_portable(xf), exact));
        else worst_absolute = std::max(worst_absolute, err / std::fabs(exact));
    }
    CHECK(worst_ulp_near_one <= 3.0);  // the (m−1)/(m+1) division costs one more ulp near 1
    CHECK(worst_absolute < 2.5e-7);    // relative: about 2 ulp
    CHECK(detail::log_portable(1.0f) == 0.0f);
    CHECK(detail::log_portable(0.0f) == -std::numeric_limits<float>::infinity());
    CHECK(detail::is_nan(detail::log_portable(-1.0f)));
    CHECK(detail::is_nan(detail::log_portable(std::numeric_limits<float>::quiet_NaN())));
    CHECK(detail::log_portable(std::numeric_limits<float>::infinity()) == std::numeric_limits<float>::infinity());
}

TEST_CASE("a projection taken a few columns at a time has project_pose()'s bits") {
    // project_pose_columns() in steps of four columns (the tail of single
    // columns last), as spread work takes it (AnnotatorConfig::spread_work).
    std::mt19937 rng(3);
    std::normal_distribution<float> normal(0.0f, 0.3f);
    for (const std::size_t joints : {3u, 7u, 31u}) {  // D = 9, 21, 93: a tail each
        host::ModelData data;
        for (std::size_t j = 0; j < joints; ++j) data.pose_joints.push_back(static_cast<std::uint16_t>(j));
        const std::size_t D = 3 * joints, d = 5;
        data.feature_dim = static_cast<std::uint16_t>(d);
        for (std::size_t i = 0; i < D; ++i) data.projection_mean.push_back(normal(rng));
        for (std::size_t i = 0; i < D * d; ++i) data.projection_matrix.push_back(normal(rng));
        const ModelView view = data.view();
        REQUIRE(view.input_dim() == D);
        std::vector<float> pose(D), want(d), got(d, 1.0f);
        for (int sample = 0; sample < 30; ++sample) {
            for (float& v : pose) v = normal(rng);
            REQUIRE(project_pose(view, pose.data(), want.data()) == Status::ok);
            std::size_t first = 0, calls = 0;
            while (first < D) {
                const std::size_t groups = 1 + static_cast<std::size_t>(rng() % 3);
                const std::size_t last = (D - first) / 4 <= groups ? D : first + 4 * groups;
                project_pose_columns(view, pose.data(), got.data(), first, last);
                first = last;
                ++calls;
            }
            CHECK(calls >= (joints > 3 ? 2u : 1u));
            for (std::size_t r = 0; r < d; ++r) CHECK(std::memcmp(&got[r], &want[r], sizeof(float)) == 0);
        }
    }
}
