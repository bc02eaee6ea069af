// actionstring host library — k-means, for the GMM's start (gmm_em.cpp) and
// the exemplars (exemplars.cpp).
#pragma once

#include <random>
#include <vector>

#include <Eigen/Core>

namespace actionstring {
namespace host {

/// k-means++ seeding followed by ten Lloyd steps over the columns of `x`
/// (n ≥ k ≥ 1 samples). Sets `centres` (rows of x × k) and returns each
/// sample's centre. Deterministic for the generator's state; a centre left
/// without samples keeps its place.
std::vector<int> kmeans_plus_plus(const Eigen::MatrixXd& x, int k, std::mt19937_64& rng, Eigen::MatrixXd& centres);

}  // namespace host
}  // namespace actionstring
