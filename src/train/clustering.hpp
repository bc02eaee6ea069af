// actionstring host library — clustering for training.
#pragma once

#include <cstddef>
#include <functional>
#include <cstdint>
#include <vector>

#include "actionstring/model.hpp"
#include "actionstring/string_distance.hpp"

namespace actionstring {
namespace host {

/// The cluster tree in the runtime's table layout.
struct ClusterTree {
    std::vector<float> centroids;        ///< node × dim.
    std::vector<std::int16_t> children;  ///< node × 2, −1 at leaves.
    std::vector<Character> characters;   ///< Leaf characters, numbered breadth-first.
    int character_count = 0;
};

/// Whether the L1 diameter of `members` is ≥ ε. Exact up to `exact_limit`
/// members; above it, when the cheap bounds disagree, it answers yes, so the
/// tree never splits less than the exact rule would.
bool diameter_reaches(const std::vector<float>& features, std::size_t dim, const std::vector<std::size_t>& members,
                      double epsilon, std::size_t exact_limit);

/// Top-down: a cluster whose L1 diameter reaches ε is split in two by 2-means
/// (k-means++ seeded, squared Euclidean: the runtime's descent metric, ties
/// to the left). Nodes are created breadth-first; at most `max_leaves`.
ClusterTree build_cluster_tree(const std::vector<float>& features, std::size_t dim, double epsilon, int max_leaves,
                               std::uint32_t seed, std::size_t exact_limit = 3000);

/// Agglomerative clustering (paper §4.3): repeatedly merge the two clusters
/// whose centroids are nearest while that distance is ≤ σ; a cluster's
/// centroid is its medoid, the member whose largest distance to the other
/// members is smallest. Returns every cluster (singletons included), medoid first.
///
/// Symmetrised string distances between every pair of strings:
/// ½ (d(a, b) + d(b, a)) with the runtime's string_distance(), ∞ when either is
/// empty. The second direction is skipped where it is the same computation
/// (strings of different lengths: A1 is the shorter either way, unless the
/// query's length normalises) or provably the same value (equal lengths under
/// `whole` without normalisation and a symmetric W: the transposed table holds
/// the same minima), so results are bit-identical to computing both. Rows run
/// on up to `workers` threads. Throws std::invalid_argument for a string too
/// long to compare.
std::vector<std::vector<double>> pairwise_string_distances(const ModelView& model,
                                                           const std::vector<std::vector<Character>>& strings,
                                                           const MatchOptions& match, std::size_t workers = 1);

/// A bound on what the clusters cost. Once the nearest pair is farther than σ,
/// `over` is asked whether the clusters (members, and each one's medoid) still
/// cost too much: merging then goes on past σ, nearest pair among those
/// `may_merge` allows (any, when empty) first, until `over` says no or no pair
/// may merge.
struct ClusterBudget {
    std::function<bool(const std::vector<std::vector<std::size_t>>& clusters, const std::vector<std::size_t>& medoids)>
        over;
    std::function<bool(const std::vector<std::size_t>& a, const std::vector<std::size_t>& b)> may_merge;
};

/// `last_merge`, when given, receives the distance of the last merge made (0 when none was).
std::vector<std::vector<std::size_t>> agglomerate(const std::vector<std::vector<double>>& distance, double sigma,
                                                  const ClusterBudget& budget = {}, double* last_merge = nullptr);

}  // namespace host
}  // namespace actionstring
