// actionstring host library — the GMM of key-poses fitted by EM (design §1.3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "actionstring/model.hpp"

namespace actionstring {
namespace host {

/// What fitting the GMM did, for reports and tests.
struct EmReport {
    std::vector<double> objective;       ///< Penalised log-likelihood after each iteration.
    std::vector<double> log_likelihood;  ///< Plain log-likelihood after each iteration.
    std::vector<int> reseeded;           ///< Iterations at which an emptied component was re-seeded.
    int dropped = 0;                     ///< Components dropped after collapsing a third time.
    bool converged = false;
};

/// One EM iteration, as it ends (for progress reports).
struct EmProgress {
    int iteration = 0;         ///< 0 is the fit of the k-means start.
    int max_iterations = 0;
    int components = 0;        ///< J now (a component that collapses a third time is dropped).
    double objective = 0.0;    ///< Penalised log-likelihood.
    double change = 0.0;       ///< |objective − previous| / |objective|; infinity at iteration 0.
    bool reseeded = false;     ///< An emptied component was re-seeded this iteration.
    bool converged = false;    ///< The change is within the tolerance: this was the last iteration.
};

/// A GMM fitted in double precision.
struct GmmFit {
    std::vector<Eigen::VectorXd> means;
    std::vector<Eigen::MatrixXd> covariances;
    std::vector<double> weights;
    EmReport report;
};

/// Fits a J-component GMM to the columns of `samples` (d × N) by EM from a
/// k-means++ start (seeded). The covariance update is the MAP estimate
/// Σ_j = (S_j + λ I) / N_j with λ = covariance_floor · N / J, so the objective
/// log-likelihood − ½ λ Σ_j tr(Σ_j⁻¹) never decreases. A component left with
/// (almost) no responsibility is re-seeded at the worst-explained sample with
/// the other components' mean covariance and weight 1/J; one that collapses a
/// third time is dropped, so the fit may return fewer than J components.
/// Both are recorded in the report (the objective may drop at those iterations). Throws std::invalid_argument for fewer samples
/// than components or non-finite samples.
///
/// Each iteration's M-step and E-step run component by component on up to
/// `workers` threads; every component's sums keep one order and the shared
/// sums run in component order afterwards, so the fit is the same for any
/// number of workers. `progress`, when set, is called after every iteration
/// (from the calling thread).
GmmFit fit_gmm(const Eigen::MatrixXd& samples, int components, Covariance covariance, double covariance_floor,
               int max_iterations, double tolerance, std::uint32_t seed, std::size_t workers = 1,
               const std::function<void(const EmProgress&)>& progress = {});

}  // namespace host
}  // namespace actionstring
