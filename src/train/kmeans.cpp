// k-means: k-means++ seeding, then a few Lloyd steps.
#include "train/kmeans.hpp"

#include <random>

namespace actionstring {
namespace host {

std::vector<int> kmeans_plus_plus(const Eigen::MatrixXd& x, int k, std::mt19937_64& rng, Eigen::MatrixXd& centres) {
    const Eigen::Index n = x.cols();
    centres.resize(x.rows(), k);
    std::uniform_int_distribution<Eigen::Index> first(0, n - 1);
    centres.col(0) = x.col(first(rng));
    Eigen::VectorXd nearest = (x.colwise() - centres.col(0)).colwise().squaredNorm().transpose();
    for (int c = 1; c < k; ++c) {
        const double total = nearest.sum();
        Eigen::Index pick = 0;
        if (total > 0) {
            double target = std::uniform_real_distribution<double>(0.0, total)(rng);
            for (pick = 0; pick < n - 1; ++pick) {
                target -= nearest[pick];
                if (target <= 0) break;
            }
        } else {
            pick = first(rng);  // all samples coincide with a centre already
        }
        centres.col(c) = x.col(pick);
        nearest = nearest.cwiseMin((x.colwise() - centres.col(c)).colwise().squaredNorm().transpose());
    }
    std::vector<int> assignment(static_cast<std::size_t>(n), 0);
    for (int step = 0; step < 10; ++step) {
        for (Eigen::Index i = 0; i < n; ++i) {
            Eigen::Index best = 0;
            (centres.colwise() - x.col(i)).colwise().squaredNorm().minCoeff(&best);
            assignment[static_cast<std::size_t>(i)] = static_cast<int>(best);
        }
        Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(x.rows(), k);
        Eigen::VectorXd counts = Eigen::VectorXd::Zero(k);
        for (Eigen::Index i = 0; i < n; ++i) {
            sums.col(assignment[static_cast<std::size_t>(i)]) += x.col(i);
            counts[assignment[static_cast<std::size_t>(i)]] += 1;
        }
        for (int c = 0; c < k; ++c)
            if (counts[c] > 0) centres.col(c) = sums.col(c) / counts[c];
    }
    return assignment;
}

}  // namespace host
}  // namespace actionstring
