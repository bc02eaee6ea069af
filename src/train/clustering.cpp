// The ε cluster tree over pose features (paper §4.1) and the agglomeration of
// training strings into representatives (paper §4.3).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "train/clustering.hpp"

#include "common/parallel.hpp"

namespace actionstring {
namespace host {
namespace {

double l1(const float* a, const float* b, std::size_t n) {
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) sum += std::fabs(static_cast<double>(a[i]) - static_cast<double>(b[i]));
    return sum;
}

double l2sq(const float* a, const double* b, std::size_t n) {
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double d = static_cast<double>(a[i]) - b[i];
        sum += d * d;
    }
    return sum;
}

}  // namespace

bool diameter_reaches(const std::vector<float>& features, std::size_t dim, const std::vector<std::size_t>& members,
                      double epsilon, std::size_t exact_limit) {
    if (members.size() < 2) return false;
    auto at = [&](std::size_t m) { return features.data() + members[m] * dim; };
    // Lower bound: a far pair found from an arbitrary start (two sweeps).
    std::size_t far = 0;
    double best = -1;
    for (std::size_t m = 0; m < members.size(); ++m) {
        const double d = l1(at(0), at(m), dim);
        if (d > best) best = d, far = m;
    }
    double lower = 0;
    for (std::size_t m = 0; m < members.size(); ++m) lower = std::max(lower, l1(at(far), at(m), dim));
    if (lower >= epsilon) return true;
    // Upper bound: twice the largest distance to the coordinate-wise median (triangle inequality).
    std::vector<float> median(dim);
    std::vector<float> column(members.size());
    for (std::size_t k = 0; k < dim; ++k) {
        for (std::size_t m = 0; m < members.size(); ++m) column[m] = at(m)[k];
        std::nth_element(column.begin(), column.begin() + static_cast<long>(column.size() / 2), column.end());
        median[k] = column[column.size() / 2];
    }
    double radius = 0;
    for (std::size_t m = 0; m < members.size(); ++m) radius = std::max(radius, l1(median.data(), at(m), dim));
    if (2 * radius < epsilon) return false;
    // Between the bounds: exact when affordable, otherwise split (never less than the exact rule).
    if (members.size() > exact_limit) return true;
    for (std::size_t a = 0; a < members.size(); ++a)
        for (std::size_t b = a + 1; b < members.size(); ++b)
            if (l1(at(a), at(b), dim) >= epsilon) return true;
    return false;
}

ClusterTree build_cluster_tree(const std::vector<float>& features, std::size_t dim, double epsilon, int max_leaves,
                               std::uint32_t seed, std::size_t exact_limit) {
    if (dim == 0 || features.size() % dim != 0 || features.empty())
        throw std::invalid_argument("cluster tree: no features");
    const std::size_t n = features.size() / dim;
    std::mt19937_64 rng(seed);
    ClusterTree tree;
    struct Pending {
        std::size_t node;
        std::vector<std::size_t> members;
    };
    auto add_node = [&](const std::vector<std::size_t>& members) {
        std::vector<double> centroid(dim, 0.0);
        for (std::size_t m : members)
            for (std::size_t k = 0; k < dim; ++k) centroid[k] += static_cast<double>(features[m * dim + k]);
        for (double& c : centroid) c /= static_cast<double>(members.size());
        for (double c : centroid) tree.centroids.push_back(static_cast<float>(c));
        tree.children.push_back(-1);
        tree.children.push_back(-1);
        tree.characters.push_back(0);
        return tree.characters.size() - 1;
    };
    std::vector<std::size_t> all(n);
    for (std::size_t i = 0; i < n; ++i) all[i] = i;
    // Breadth-first, so children always get larger indices than their parent
    // and a leaf cap keeps the shallowest splits.
    std::vector<Pending> queue;
    queue.push_back({add_node(all), all});
    std::size_t head = 0;
    int leaves = 1;
    while (head < queue.size()) {
        Pending current = std::move(queue[head++]);
        if (leaves >= max_leaves || !diameter_reaches(features, dim, current.members, epsilon, exact_limit)) continue;
        // 2-means with k-means++ seeding; squared Euclidean, the runtime's descent metric.
        const std::size_t count = current.members.size();
        std::vector<double> centre[2] = {std::vector<double>(dim), std::vector<double>(dim)};
        const std::size_t first = current.members[std::uniform_int_distribution<std::size_t>(0, count - 1)(rng)];
        for (std::size_t k = 0; k < dim; ++k) centre[0][k] = features[first * dim + k];
        std::vector<double> weight(count);
        double total = 0;
        for (std::size_t m = 0; m < count; ++m)
            total += weight[m] = l2sq(features.data() + current.members[m] * dim, centre[0].data(), dim);
        if (!(total > 0)) continue;  // every member identical: cannot split
        double target = std::uniform_real_distribution<double>(0.0, total)(rng);
        std::size_t second = count - 1;
        for (std::size_t m = 0; m < count; ++m) {
            target -= weight[m];
            if (target <= 0) {
                second = m;
                break;
            }
        }
        for (std::size_t k = 0; k < dim; ++k) centre[1][k] = features[current.members[second] * dim + k];
        std::vector<std::uint8_t> side(count, 0);
        for (int iteration = 0; iteration < 100; ++iteration) {
            bool changed = false;
            for (std::size_t m = 0; m < count; ++m) {
                const float* f = features.data() + current.members[m] * dim;
                // Ties go left, as in the runtime's descent.
                const std::uint8_t s = l2sq(f, centre[1].data(), dim) < l2sq(f, centre[0].data(), dim) ? 1 : 0;
                changed = changed || s != side[m] || iteration == 0;
                side[m] = s;
            }
            if (!changed) break;
            for (int c = 0; c < 2; ++c) {
                std::vector<double> sum(dim, 0.0);
                std::size_t members = 0;
                for (std::size_t m = 0; m < count; ++m)
                    if (side[m] == c) {
                        ++members;
                        for (std::size_t k = 0; k < dim; ++k)
                            sum[k] += static_cast<double>(features[current.members[m] * dim + k]);
                    }
                if (members > 0)
                    for (std::size_t k = 0; k < dim; ++k) centre[c][k] = sum[k] / static_cast<double>(members);
            }
        }
        std::vector<std::size_t> parts[2];
        for (std::size_t m = 0; m < count; ++m) parts[side[m]].push_back(current.members[m]);
        if (parts[0].empty() || parts[1].empty()) continue;
        if (tree.characters.size() + 2 > 32767) break;
        const std::size_t left = add_node(parts[0]);
        const std::size_t right = add_node(parts[1]);
        tree.children[2 * current.node] = static_cast<std::int16_t>(left);
        tree.children[2 * current.node + 1] = static_cast<std::int16_t>(right);
        queue.push_back({left, std::move(parts[0])});
        queue.push_back({right, std::move(parts[1])});
        ++leaves;
    }
    int next = 0;
    for (std::size_t node = 0; node < tree.characters.size(); ++node)
        if (tree.children[2 * node] < 0) tree.characters[node] = static_cast<Character>(next++);
    tree.character_count = next;
    return tree;
}

std::vector<std::vector<double>> pairwise_string_distances(const ModelView& model,
                                                           const std::vector<std::vector<Character>>& strings,
                                                           const MatchOptions& match, std::size_t workers) {
    const CharacterWeights weights = character_weights(model);
    const bool transpose_same = match.variant == MatchVariant::whole &&
                                match.normalization == LengthNormalization::none &&
                                model.character_distances_symmetric();
    const std::size_t n = strings.size();
    std::vector<std::vector<double>> distance(n, std::vector<double>(n, 0.0));
    std::vector<int> failed(n, 0);
    // Row a fills distance[a][b] for b > a; the lower triangle is copied after.
    parallel_for(n, workers, [&](std::size_t a) {
        std::vector<detail::Cell> workspace;
        auto measure = [&](const std::vector<Character>& x, const std::vector<Character>& y) {
            workspace.resize(string_distance_cells(x.size(), y.size()));
            float value = 0;
            if (string_distance(x.data(), x.size(), y.data(), y.size(), weights, match, workspace.data(), &value) !=
                Status::ok)
                failed[a] = 1;
            return static_cast<double>(value);
        };
        for (std::size_t b = a + 1; b < n; ++b) {
            const std::vector<Character>&x = strings[a], &y = strings[b];
            if (x.empty() || y.empty()) {
                distance[a][b] = std::numeric_limits<double>::infinity();
                continue;
            }
            const double there = measure(x, y);
            const bool same = x.size() != y.size() ? match.normalization != LengthNormalization::query : transpose_same;
            distance[a][b] = 0.5 * (there + (same ? there : measure(y, x)));
        }
    });
    for (std::size_t a = 0; a < n; ++a) {
        if (failed[a]) throw std::invalid_argument("a training string is too long to compare");
        for (std::size_t b = a + 1; b < n; ++b) distance[b][a] = distance[a][b];
    }
    return distance;
}

std::vector<std::vector<std::size_t>> agglomerate(const std::vector<std::vector<double>>& distance, double sigma,
                                                  const ClusterBudget& budget, double* last_merge) {
    if (last_merge != nullptr) *last_merge = 0.0;
    const std::size_t n = distance.size();
    std::vector<std::vector<std::size_t>> clusters(n);
    std::vector<std::size_t> medoid(n);
    for (std::size_t i = 0; i < n; ++i) {
        clusters[i] = {i};
        medoid[i] = i;
    }
    for (;;) {
        double best = std::numeric_limits<double>::infinity();
        std::size_t a = 0, b = 0;
        for (std::size_t i = 0; i < clusters.size(); ++i)
            for (std::size_t j = i + 1; j < clusters.size(); ++j) {
                const double d = distance[medoid[i]][medoid[j]];
                if (d < best) best = d, a = i, b = j;
            }
        if (clusters.size() < 2 || a == b) break;  // one cluster, or no two comparable
        if (!(best <= sigma)) {
            // Past σ only while over the budget, and only pairs it lets merge.
            if (!budget.over || !budget.over(clusters, medoid)) break;
            if (budget.may_merge) {
                best = std::numeric_limits<double>::infinity();
                a = b = 0;
                for (std::size_t i = 0; i < clusters.size(); ++i)
                    for (std::size_t j = i + 1; j < clusters.size(); ++j) {
                        const double d = distance[medoid[i]][medoid[j]];
                        if (d < best && budget.may_merge(clusters[i], clusters[j])) best = d, a = i, b = j;
                    }
                if (a == b) break;  // nothing may merge
            }
        }
        if (last_merge != nullptr) *last_merge = best;
        clusters[a].insert(clusters[a].end(), clusters[b].begin(), clusters[b].end());
        std::sort(clusters[a].begin(), clusters[a].end());
        clusters.erase(clusters.begin() + static_cast<long>(b));
        medoid.erase(medoid.begin() + static_cast<long>(b));
        // Medoid: the member whose largest distance to the other members is smallest (first on ties).
        double smallest = std::numeric_limits<double>::infinity();
        for (std::size_t m : clusters[a]) {
            double largest = 0;
            for (std::size_t o : clusters[a]) largest = std::max(largest, distance[m][o]);
            if (largest < smallest) smallest = largest, medoid[a] = m;
        }
    }
    // Report each cluster with its medoid first.
    for (std::size_t c = 0; c < clusters.size(); ++c) {
        auto& members = clusters[c];
        std::iter_swap(members.begin(), std::find(members.begin(), members.end(), medoid[c]));
    }
    return clusters;
}

}  // namespace host
}  // namespace actionstring
