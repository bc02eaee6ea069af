// Training's clip descriptor: ridge regression on the clips' pyramids.
#include "train/descriptor.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "actionstring/descriptor.hpp"

namespace actionstring {
namespace host {

void set_descriptor(ModelData& m, const std::vector<std::vector<float>>& features, const std::vector<LabelId>& labels,
                    std::size_t levels, std::size_t dims, double ridge, double weight) {
    m.descriptor_weight = 0.0f;
    m.descriptor_levels = 0;
    m.descriptor_dim = 0;
    m.descriptor_weights.clear();
    m.descriptor_bias.clear();
    if (levels == 0 || !(weight > 0)) return;
    const std::size_t d = m.feature_dim, k_dims = dims == 0 ? d : dims;
    if (levels > 8) throw std::invalid_argument("descriptor: at most 8 levels, not " + std::to_string(levels));
    if (k_dims > d)
        throw std::invalid_argument("descriptor: " + std::to_string(k_dims) +
                                    " dimensions asked for, but the feature has " + std::to_string(d));
    if (k_dims == 0 || k_dims > max_descriptor_dims)
        throw std::invalid_argument("descriptor: it reads 1 to 64 of the feature's coordinates, not " +
                                    std::to_string(k_dims) + " (set descriptor-dims)");
    if (!(ridge > 0) || !std::isfinite(ridge)) throw std::invalid_argument("descriptor: the ridge must be positive");
    const std::size_t L = m.label_names.size();
    const std::size_t P = descriptor_parts(levels) * descriptor_part_size(k_dims);

    // The labelled clips' descriptors, as the runtime computes them (floats), then in double.
    std::vector<std::size_t> used;
    for (std::size_t i = 0; i < features.size(); ++i)
        if (labels[i] < L && features[i].size() >= d) used.push_back(i);
    if (used.size() < 2) throw std::invalid_argument("descriptor: fewer than two labelled clips");
    const Eigen::Index n = static_cast<Eigen::Index>(used.size()), p = static_cast<Eigen::Index>(P);
    Eigen::MatrixXd x(n, p);
    std::vector<float> one(P);
    for (Eigen::Index row = 0; row < n; ++row) {
        const std::vector<float>& f = features[used[static_cast<std::size_t>(row)]];
        clip_descriptor(f.data(), f.size() / d, d, k_dims, levels, one.data());
        for (Eigen::Index c = 0; c < p; ++c) x(row, c) = static_cast<double>(one[static_cast<std::size_t>(c)]);
    }
    // Standardised coordinates. A coordinate that hardly varies (below a
    // thousandth of the widest spread) is amplified no further than that, so
    // its folded weights stay in range; one that does not vary at all gets none.
    const Eigen::RowVectorXd mean = x.colwise().mean();
    Eigen::RowVectorXd spread = ((x.rowwise() - mean).array().square().colwise().sum() / static_cast<double>(n)).sqrt();
    const double widest = spread.maxCoeff();
    if (!(widest > 0)) throw std::invalid_argument("descriptor: every training clip has the same descriptor");
    Eigen::RowVectorXd inverse(p);
    for (Eigen::Index c = 0; c < p; ++c) inverse[c] = spread[c] > 0 ? 1.0 / std::max(spread[c], 1e-3 * widest) : 0.0;
    const Eigen::MatrixXd z = (x.rowwise() - mean).array().rowwise() * inverse.array();

    // Targets ±1, centred (the intercept is their mean, unpenalised).
    Eigen::MatrixXd y = Eigen::MatrixXd::Constant(n, static_cast<Eigen::Index>(L), -1.0);
    for (Eigen::Index row = 0; row < n; ++row) y(row, labels[used[static_cast<std::size_t>(row)]]) = 1.0;
    const Eigen::RowVectorXd intercept = y.colwise().mean();
    y.rowwise() -= intercept;

    // W = (ZᵀZ + λI)⁻¹ Zᵀ Y, through the smaller of the two systems (the same solution).
    Eigen::MatrixXd w;
    if (n <= p) {
        Eigen::MatrixXd gram = z * z.transpose();
        gram.diagonal().array() += ridge;
        w = z.transpose() * gram.ldlt().solve(y);
    } else {
        Eigen::MatrixXd gram = z.transpose() * z;
        gram.diagonal().array() += ridge;
        w = gram.ldlt().solve(z.transpose() * y);
    }
    if (!w.allFinite()) throw std::invalid_argument("descriptor: the ridge regression did not give finite weights");

    // Folded: score(l) = intercept(l) + Σ_c w(c, l) (x_c − mean_c) / spread_c.
    m.descriptor_weights.assign(L * P, 0.0f);
    m.descriptor_bias.assign(L, 0.0f);
    for (std::size_t l = 0; l < L; ++l) {
        double bias = intercept[static_cast<Eigen::Index>(l)];
        for (Eigen::Index c = 0; c < p; ++c) {
            const double folded = w(c, static_cast<Eigen::Index>(l)) * inverse[c];
            if (!(std::fabs(folded) < 1e5))
                throw std::invalid_argument(
                    "descriptor: a weight beyond 1e5 (features of a tiny scale?); "
                    "try fewer descriptor-dims or a larger descriptor-ridge");
            m.descriptor_weights[l * P + static_cast<std::size_t>(c)] = static_cast<float>(folded);
            bias -= folded * mean[c];
        }
        m.descriptor_bias[l] = static_cast<float>(bias);
    }
    m.descriptor_levels = static_cast<std::uint8_t>(levels);
    m.descriptor_dim = static_cast<std::uint16_t>(k_dims == d ? 0 : k_dims);
    m.descriptor_weight = static_cast<float>(weight);
}

}  // namespace host
}  // namespace actionstring
