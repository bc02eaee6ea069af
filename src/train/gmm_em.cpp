// GMM fitting by EM, in double precision.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

#include <Eigen/Cholesky>

#include "common/parallel.hpp"
#include "train/gmm_em.hpp"
#include "train/kmeans.hpp"

namespace actionstring {
namespace host {
namespace {

constexpr double kLog2Pi = 1.8378770664093454836;
// Samples per block in the E- and M-steps: a d × block slice of doubles stays in
// the cache (24 × 1024 × 8 = 192 KiB at d = 24).
constexpr Eigen::Index kSampleBlock = 1024;

}  // namespace

GmmFit fit_gmm(const Eigen::MatrixXd& x, int components, Covariance covariance, double covariance_floor,
               int max_iterations, double tolerance, std::uint32_t seed, std::size_t workers,
               const std::function<void(const EmProgress&)>& progress) {
    const Eigen::Index d = x.rows(), n = x.cols();
    const int J = components;
    if (J < 1) throw std::invalid_argument("the GMM needs at least one component");
    if (n < J)
        throw std::invalid_argument("the GMM has " + std::to_string(J) + " components but only " + std::to_string(n) +
                                    " training samples: use fewer components or more data");
    if (!x.allFinite()) throw std::invalid_argument("GMM training samples contain non-finite values");
    if (!(covariance_floor > 0)) throw std::invalid_argument("the covariance floor must be positive");
    const bool diagonal = covariance == Covariance::diagonal;
    const double lambda = covariance_floor * static_cast<double>(n) / J;

    std::mt19937_64 rng(seed);
    Eigen::MatrixXd centres;
    const std::vector<int> assignment = kmeans_plus_plus(x, J, rng, centres);

    GmmFit fit;
    fit.means.assign(static_cast<std::size_t>(J), Eigen::VectorXd::Zero(d));
    fit.covariances.assign(static_cast<std::size_t>(J), Eigen::MatrixXd::Identity(d, d));
    fit.weights.assign(static_cast<std::size_t>(J), 1.0 / J);
    // Start from the hard k-means clusters: one M-step with 0/1 responsibilities.
    // Responsibilities are n × J: a component's column is contiguous, so the
    // M-step of one component streams n doubles instead of striding over all
    // n × J (and the E-step's workers write separate columns).
    Eigen::MatrixXd resp = Eigen::MatrixXd::Zero(n, J);
    for (Eigen::Index i = 0; i < n; ++i) resp(i, assignment[static_cast<std::size_t>(i)]) = 1.0;

    Eigen::VectorXd worst_fit(n);  // per-sample log-likelihood, to re-seed empty components
    worst_fit.setZero();
    std::vector<int> reseed_count(static_cast<std::size_t>(J), 0);
    double previous = -std::numeric_limits<double>::infinity();
    for (int iteration = 0; iteration <= max_iterations; ++iteration) {
        // M-step (MAP covariance), component by component on the workers.
        bool reseeded = false;
        int current = static_cast<int>(fit.means.size());
        std::vector<char> empty(static_cast<std::size_t>(current), 0);  // (not vector<bool>: written by threads)
        parallel_for(static_cast<std::size_t>(current), workers, [&](std::size_t component) {
            const auto j = static_cast<Eigen::Index>(component);
            const double nj = resp.col(j).sum();
            if (nj < 1e-6 * static_cast<double>(n) || nj < 1e-3) {
                empty[component] = 1;
                return;
            }
            const Eigen::VectorXd mean = x * resp.col(j) / nj;
            // The weighted scatter Σ_i r_ij (x_i − μ)(x_i − μ)ᵀ, a block of samples at a
            // time: the centred block stays in the cache, where a d × N centred copy
            // (and its weighted copy) per component and iteration would not, and cost
            // the kernel a page fault per 4 KiB. The full covariance takes a symmetric
            // rank update of the block scaled by √r (half the products of a GEMM).
            Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(d, diagonal ? 1 : d);
            Eigen::MatrixXd centred;
            for (Eigen::Index first = 0; first < n; first += kSampleBlock) {
                const Eigen::Index count = std::min(kSampleBlock, n - first);
                const auto r = resp.col(j).segment(first, count).transpose().array();
                centred = x.middleCols(first, count).colwise() - mean;
                if (diagonal) {
                    scatter.col(0).noalias() += centred.array().square().matrix() * r.matrix().transpose();
                } else {
                    centred.array().rowwise() *= r.sqrt();
                    scatter.selfadjointView<Eigen::Lower>().rankUpdate(centred);
                }
            }
            Eigen::MatrixXd cov;
            if (diagonal) {
                cov = Eigen::MatrixXd(((scatter.col(0).array() + lambda) / nj).matrix().asDiagonal());
            } else {
                cov = scatter.selfadjointView<Eigen::Lower>();
                cov.diagonal().array() += lambda;
                cov /= nj;
            }
            fit.means[component] = mean;
            fit.covariances[component] = cov;
            fit.weights[component] = nj / static_cast<double>(n);
        });
        // Recovery for components that lost (almost) every sample: re-seed at the
        // sample the mixture explains worst, with the others' mean covariance and
        // an average weight; one that collapses a third time is dropped (J shrinks).
        for (int j = current - 1; j >= 0; --j) {
            if (!empty[static_cast<std::size_t>(j)]) continue;
            reseeded = true;
            if (++reseed_count[static_cast<std::size_t>(j)] > 2 || current == 1) {
                fit.means.erase(fit.means.begin() + j);
                fit.covariances.erase(fit.covariances.begin() + j);
                fit.weights.erase(fit.weights.begin() + j);
                reseed_count.erase(reseed_count.begin() + j);
                fit.report.dropped += 1;
                --current;
                continue;
            }
            Eigen::Index worst = 0;
            worst_fit.minCoeff(&worst);
            worst_fit[worst] = std::numeric_limits<double>::infinity();
            Eigen::MatrixXd typical = Eigen::MatrixXd::Zero(d, d);
            int others = 0;
            for (int k = 0; k < current; ++k)
                if (!empty[static_cast<std::size_t>(k)]) {
                    typical += fit.covariances[static_cast<std::size_t>(k)];
                    ++others;
                }
            fit.means[static_cast<std::size_t>(j)] = x.col(worst);
            fit.covariances[static_cast<std::size_t>(j)] =
                others > 0 ? Eigen::MatrixXd(typical / others)
                           : Eigen::MatrixXd(lambda * Eigen::MatrixXd::Identity(d, d));
            fit.weights[static_cast<std::size_t>(j)] = 1.0 / current;
        }
        if (reseeded) {
            const double total = std::accumulate(fit.weights.begin(), fit.weights.end(), 0.0);
            for (double& w : fit.weights) w /= total;
            fit.report.reseeded.push_back(iteration);
        }
        const int J_now = current;
        // E-step in the log domain, component by component on the workers; the
        // penalty's terms are summed afterwards in component order.
        Eigen::MatrixXd log_joint(n, J_now);
        std::vector<double> penalties(static_cast<std::size_t>(J_now), 0.0);
        parallel_for(static_cast<std::size_t>(J_now), workers, [&](std::size_t component) {
            const auto j = static_cast<Eigen::Index>(component);
            double& penalty = penalties[component];
            const Eigen::MatrixXd& cov = fit.covariances[component];
            const Eigen::VectorXd& mean = fit.means[component];
            Eigen::RowVectorXd q(n);
            double log_det = 0;
            if (diagonal) {
                const Eigen::VectorXd inv = cov.diagonal().cwiseInverse();
                const Eigen::MatrixXd centred = x.colwise() - mean;
                q = (centred.array().square().colwise() * inv.array()).colwise().sum().matrix();
                log_det = cov.diagonal().array().log().sum();
                penalty += inv.sum();
            } else {
                Eigen::LLT<Eigen::MatrixXd> llt(cov);
                if (llt.info() != Eigen::Success)
                    throw std::runtime_error("EM: a covariance lost positive definiteness");
                // Samples a block at a time, so the d × block temporaries stay in
                // the cache (each sample's distance is its own column: the same
                // numbers as one solve over all of them).
                Eigen::MatrixXd solved;
                for (Eigen::Index first = 0; first < n; first += kSampleBlock) {
                    const Eigen::Index count = std::min(kSampleBlock, n - first);
                    solved = x.middleCols(first, count).colwise() - mean;
                    llt.matrixL().solveInPlace(solved);
                    q.segment(first, count) = solved.colwise().squaredNorm();
                }
                log_det = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
                penalty += llt.solve(Eigen::MatrixXd::Identity(d, d)).trace();
            }
            log_joint.col(j) = ((std::log(fit.weights[component]) - 0.5 * (static_cast<double>(d) * kLog2Pi + log_det)) -
                                0.5 * q.array())
                                   .transpose();
        });
        double penalty = 0;
        for (const double term : penalties) penalty += term;
        const Eigen::VectorXd peak = log_joint.rowwise().maxCoeff();
        const Eigen::VectorXd lse = peak.array() + (log_joint.colwise() - peak).array().exp().rowwise().sum().log();
        resp = (log_joint.colwise() - lse).array().exp().matrix();
        worst_fit = lse;
        const double log_likelihood = lse.sum();
        const double objective = log_likelihood - 0.5 * lambda * penalty;
        if (!std::isfinite(objective)) throw std::runtime_error("EM: the log-likelihood is not finite");
        fit.report.log_likelihood.push_back(log_likelihood);
        fit.report.objective.push_back(objective);
        const double change = iteration == 0 ? std::numeric_limits<double>::infinity()
                                             : std::fabs(objective - previous) / std::fabs(objective);
        const bool converged =
            iteration > 0 && !reseeded && std::fabs(objective - previous) <= tolerance * std::fabs(objective);
        if (progress) progress(EmProgress{iteration, max_iterations, J_now, objective, change, reseeded, converged});
        if (converged) {
            fit.report.converged = true;
            break;
        }
        previous = objective;
    }
    return fit;
}

}  // namespace host
}  // namespace actionstring
