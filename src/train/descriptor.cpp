// Training's clip descriptors: ridge regression on the clips' pyramids and
// on their motion directions.
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

namespace {

// One ridge regression per label on the clips' summaries `x` (a row each,
// `labels[row]` its label, < L): every coordinate standardised over the
// clips, target +1 for the label's clips and −1 for the others, an
// unpenalised intercept, penalty `ridge` on the squared weights. Gives
// L × P weights (label by label) and L biases with the standardisation folded
// in. `what` and `advice` word the errors.
void fit_ridge(const Eigen::MatrixXd& x, const std::vector<LabelId>& labels, std::size_t L, double ridge,
               const std::string& what, const std::string& advice, std::vector<float>& weights,
               std::vector<float>& bias) {
    const Eigen::Index n = x.rows(), p = x.cols();
    const std::size_t P = static_cast<std::size_t>(p);
    // Standardised coordinates. A coordinate that hardly varies (below a
    // thousandth of the widest spread) is amplified no further than that, so
    // its folded weights stay in range; one that does not vary at all gets none.
    const Eigen::RowVectorXd mean = x.colwise().mean();
    Eigen::RowVectorXd spread = ((x.rowwise() - mean).array().square().colwise().sum() / static_cast<double>(n)).sqrt();
    const double widest = spread.maxCoeff();
    if (!(widest > 0)) throw std::invalid_argument(what + ": every training clip has the same descriptor");
    Eigen::RowVectorXd inverse(p);
    for (Eigen::Index c = 0; c < p; ++c) inverse[c] = spread[c] > 0 ? 1.0 / std::max(spread[c], 1e-3 * widest) : 0.0;
    const Eigen::MatrixXd z = (x.rowwise() - mean).array().rowwise() * inverse.array();

    // Targets ±1, centred (the intercept is their mean, unpenalised).
    Eigen::MatrixXd y = Eigen::MatrixXd::Constant(n, static_cast<Eigen::Index>(L), -1.0);
    for (Eigen::Index row = 0; row < n; ++row) y(row, labels[static_cast<std::size_t>(row)]) = 1.0;
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
    if (!w.allFinite()) throw std::invalid_argument(what + ": the ridge regression did not give finite weights");

    // Folded: score(l) = intercept(l) + Σ_c w(c, l) (x_c − mean_c) / spread_c.
    weights.assign(L * P, 0.0f);
    bias.assign(L, 0.0f);
    for (std::size_t l = 0; l < L; ++l) {
        double sum = intercept[static_cast<Eigen::Index>(l)];
        for (Eigen::Index c = 0; c < p; ++c) {
            const double folded = w(c, static_cast<Eigen::Index>(l)) * inverse[c];
            if (!(std::fabs(folded) < 1e5))
                throw std::invalid_argument(what + ": a weight beyond 1e5 (features of a tiny scale?); " + advice);
            weights[l * P + static_cast<std::size_t>(c)] = static_cast<float>(folded);
            sum -= folded * mean[c];
        }
        bias[l] = static_cast<float>(sum);
    }
}

}  // namespace

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
    std::vector<LabelId> kept;
    for (const std::size_t i : used) kept.push_back(labels[i]);
    std::vector<float> one(P);
    for (Eigen::Index row = 0; row < n; ++row) {
        const std::vector<float>& f = features[used[static_cast<std::size_t>(row)]];
        clip_descriptor(f.data(), f.size() / d, d, k_dims, levels, one.data());
        for (Eigen::Index c = 0; c < p; ++c) x(row, c) = static_cast<double>(one[static_cast<std::size_t>(c)]);
    }
    fit_ridge(x, kept, L, ridge, "descriptor", "try fewer descriptor-dims or a larger descriptor-ridge",
              m.descriptor_weights, m.descriptor_bias);
    m.descriptor_levels = static_cast<std::uint8_t>(levels);
    m.descriptor_dim = static_cast<std::uint16_t>(k_dims == d ? 0 : k_dims);
    m.descriptor_weight = static_cast<float>(weight);
}

void set_directions(ModelData& m, const std::vector<std::vector<float>>& records, const std::vector<LabelId>& labels,
                    std::size_t levels, double ridge, double weight) {
    m.direction_weight = 0.0f;
    m.direction_levels = 0;
    m.direction_weights.clear();
    m.direction_bias.clear();
    if (levels == 0 || !(weight > 0)) return;
    if (levels > 8) throw std::invalid_argument("directions: at most 8 levels, not " + std::to_string(levels));
    if (!(ridge > 0) || !std::isfinite(ridge)) throw std::invalid_argument("directions: the ridge must be positive");
    if (m.pose_joints.empty()) throw std::invalid_argument("directions: the model has no pose joints to follow");
    const std::size_t L = m.label_names.size();
    // The histograms' shape, to compute them as the runtime will (the model
    // itself gets directions only once they are fitted).
    ModelView shape = m.view();
    shape.direction_levels = static_cast<std::uint8_t>(levels);
    const std::size_t P = shape.direction_size(), width = shape.direction_record_floats();

    std::vector<std::size_t> used;
    for (std::size_t i = 0; i < records.size() && i < labels.size(); ++i)
        if (labels[i] < L && !records[i].empty() && records[i].size() % width == 0) used.push_back(i);
    if (used.size() < 2) throw std::invalid_argument("directions: fewer than two labelled clips");
    Eigen::MatrixXd x(static_cast<Eigen::Index>(used.size()), static_cast<Eigen::Index>(P));
    std::vector<LabelId> kept;
    std::vector<float> one(P);
    for (std::size_t row = 0; row < used.size(); ++row) {
        const std::vector<float>& r = records[used[row]];
        clip_directions(r.data(), r.size() / width, shape.pose_joint_count, shape.up_axis, levels, one.data());
        for (std::size_t c = 0; c < P; ++c)
            x(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(c)) = static_cast<double>(one[c]);
        kept.push_back(labels[used[row]]);
    }
    fit_ridge(x, kept, L, ridge, "directions", "try a larger direction-ridge", m.direction_weights, m.direction_bias);
    m.direction_levels = static_cast<std::uint8_t>(levels);
    m.direction_weight = static_cast<float>(weight);
}

void set_window_directions(ModelData& m, const std::vector<std::vector<float>>& records,
                           const std::vector<LabelId>& labels, std::size_t chars, double ridge) {
    m.window_direction_chars = 0;
    m.window_direction_weights.clear();
    m.window_direction_bias.clear();
    if (chars == 0) return;
    if (chars < 2 || chars > 1024)
        throw std::invalid_argument("window directions: a window of 2 to 1024 characters, not " +
                                    std::to_string(chars) + " (set direction-window)");
    if (!(ridge > 0) || !std::isfinite(ridge))
        throw std::invalid_argument("window directions: the ridge must be positive");
    if (m.pose_joints.empty()) throw std::invalid_argument("window directions: the model has no pose joints to follow");
    const std::size_t L = m.label_names.size();
    ModelView shape = m.view();
    shape.window_direction_chars = static_cast<std::uint16_t>(chars);
    const std::size_t P = shape.window_direction_size(), width = shape.direction_record_floats();

    // Every labelled clip's windows, each ending at one of its characters after the first.
    std::size_t total = 0;
    for (std::size_t i = 0; i < records.size() && i < labels.size(); ++i)
        if (labels[i] < L && records[i].size() % width == 0 && records[i].size() >= 2 * width)
            total += records[i].size() / width - 1;
    constexpr std::size_t most = 20000;
    const std::size_t every = total > most ? (total + most - 1) / most : 1;
    std::vector<std::pair<std::size_t, std::size_t>> windows;  // (clip, last character)
    std::size_t seen = 0;
    for (std::size_t i = 0; i < records.size() && i < labels.size(); ++i) {
        if (!(labels[i] < L && records[i].size() % width == 0 && records[i].size() >= 2 * width)) continue;
        for (std::size_t t = 1; t < records[i].size() / width; ++t, ++seen)
            if (seen % every == 0) windows.emplace_back(i, t);
    }
    if (windows.size() < 2) throw std::invalid_argument("window directions: fewer than two labelled windows");
    Eigen::MatrixXd x(static_cast<Eigen::Index>(windows.size()), static_cast<Eigen::Index>(P));
    std::vector<LabelId> kept;
    std::vector<float> one(P);
    for (std::size_t row = 0; row < windows.size(); ++row) {
        const auto [clip, last] = windows[row];
        const std::size_t first = last + 1 > chars ? last + 1 - chars : 0;
        clip_directions(records[clip].data() + first * width, last + 1 - first, shape.pose_joint_count, shape.up_axis,
                        1, one.data());
        for (std::size_t c = 0; c < P; ++c)
            x(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(c)) = static_cast<double>(one[c]);
        kept.push_back(labels[clip]);
    }
    fit_ridge(x, kept, L, ridge, "window directions", "try a larger direction-window-ridge", m.window_direction_weights,
              m.window_direction_bias);
    m.window_direction_chars = static_cast<std::uint16_t>(chars);
}

}  // namespace host
}  // namespace actionstring
