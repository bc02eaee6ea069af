// Training's exemplars: k-means centres of each label's features.
#include "train/exemplars.hpp"

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>

#include "actionstring/exemplars.hpp"
#include "train/kmeans.hpp"

namespace actionstring {
namespace host {

void set_exemplars(ModelData& m, const std::vector<std::vector<float>>& features, const std::vector<LabelId>& labels,
                   std::size_t per_label, std::size_t dims, double weight, std::uint32_t seed) {
    m.exemplar_weight = 0.0f;
    m.exemplar_scale = 1.0f;
    m.exemplar_dim = 0;
    m.exemplar_labels.clear();
    m.exemplars.clear();
    if (per_label == 0 || !(weight > 0)) return;
    if (dims > m.feature_dim)
        throw std::invalid_argument("exemplars: " + std::to_string(dims) +
                                    " dimensions asked for, but the feature has " + std::to_string(m.feature_dim));
    // The features keep their stride (feature_dim); the centres keep the first k coordinates.
    const std::size_t L = m.label_names.size(), d = m.feature_dim, k_dims = dims == 0 ? d : dims;
    m.exemplar_dim = static_cast<std::uint16_t>(k_dims == d ? 0 : k_dims);
    // Each label's features, as the columns of a matrix (doubles, as k-means computes).
    std::vector<std::size_t> count(L, 0);
    for (std::size_t i = 0; i < features.size(); ++i)
        if (labels[i] < L) count[labels[i]] += features[i].size() / d;
    std::size_t none = 0;  // features of no action (unknown_label)
    for (std::size_t i = 0; i < features.size(); ++i)
        if (labels[i] == unknown_label) none += features[i].size() / d;
    // Every label's centres, then no action's (the runtime finds them last).
    for (std::size_t slot = 0; slot <= L; ++slot) {
        const LabelId l = slot < L ? static_cast<LabelId>(slot) : unknown_label;
        const std::size_t n_l = slot < L ? count[slot] : none;
        if (n_l == 0) continue;
        Eigen::MatrixXd x(static_cast<Eigen::Index>(k_dims), static_cast<Eigen::Index>(n_l));
        Eigen::Index column = 0;
        for (std::size_t i = 0; i < features.size(); ++i) {
            if (labels[i] != l) continue;
            for (std::size_t at = 0; at + d <= features[i].size(); at += d, ++column)
                for (std::size_t k = 0; k < k_dims; ++k)
                    x(static_cast<Eigen::Index>(k), column) = static_cast<double>(features[i][at + k]);
        }
        Eigen::MatrixXd centres = x;
        if (n_l > per_label) {
            std::mt19937_64 rng(seed + static_cast<std::uint32_t>(slot));
            kmeans_plus_plus(x, static_cast<int>(per_label), rng, centres);
        }
        for (Eigen::Index c = 0; c < centres.cols(); ++c) {
            m.exemplar_labels.push_back(l);
            for (std::size_t k = 0; k < k_dims; ++k)
                m.exemplars.push_back(static_cast<float>(centres(static_cast<Eigen::Index>(k), c)));
        }
    }
    if (m.exemplar_labels.empty() || m.exemplar_labels.front() == unknown_label)
        throw std::invalid_argument("exemplars: no label has a training feature");
    if (m.exemplar_labels.size() > 65535)
        throw std::invalid_argument("exemplars: " + std::to_string(m.exemplar_labels.size()) +
                                    " centres are more than a model holds (65535): lower --exemplars");
    // The scale: how far a training feature lies from its own label's
    // exemplars, measured as the runtime measures (floats, its order).
    m.exemplar_weight = static_cast<float>(weight);
    const ModelView view = m.view();
    std::vector<float> distances(L);
    double own = 0.0, other = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < features.size(); ++i) {
        if (labels[i] >= L) continue;
        for (std::size_t at = 0; at + d <= features[i].size(); at += d, ++n) {
            exemplar_distances(view, &features[i][at], distances.data());
            own += distances[labels[i]];
            float nearest_other = detail::infinity();
            for (std::size_t l = 0; l < L; ++l)
                if (l != labels[i]) nearest_other = std::min(nearest_other, distances[l]);
            if (detail::is_finite(nearest_other)) other += nearest_other;
        }
    }
    double scale = n > 0 ? own / static_cast<double>(n) : 0.0;
    if (!(scale > 1e-12) && n > 0) scale = other / static_cast<double>(n);
    if (!(scale > 1e-12)) scale = 1.0;  // every feature on a centre of every label: nothing to compare
    m.exemplar_scale = static_cast<float>(scale);
}

}  // namespace host
}  // namespace actionstring
