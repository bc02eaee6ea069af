// actionstring host library — the GMM of key-poses fitted by EM (design §1.3).
#pragma once

#include <cstdint>
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
GmmFit fit_gmm(const Eigen::MatrixXd& samples, int components, Covariance covariance, double covariance_floor,
               int max_iterations, double tolerance, std::uint32_t seed);

}  // namespace host
}  // namespace actionstring
