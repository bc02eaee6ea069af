#include "actionstring_host/model_data.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>

namespace actionstring {
namespace host {

void ModelData::add_representative(const std::vector<Character>& chars, LabelId label) {
    if (chars.empty()) throw std::invalid_argument("representative string is empty");
    representative_chars.insert(representative_chars.end(), chars.begin(), chars.end());
    representative_offsets.push_back(static_cast<std::uint32_t>(representative_chars.size()));
    representative_labels.push_back(label);
}

ModelView ModelData::view() {
    label_name_pointers_.clear();
    for (const auto& name : label_names) label_name_pointers_.push_back(name.c_str());
    auto data_or_null = [](const auto& v) { return v.empty() ? nullptr : v.data(); };

    ModelView m;
    m.joint_count = joint_count;
    m.root_joint = root_joint;
    m.left_hip_joint = left_hip_joint;
    m.right_hip_joint = right_hip_joint;
    m.up_axis = up_axis;
    m.scale_mode = scale_mode;
    m.reference_scale = reference_scale;
    m.pose_joint_count = static_cast<std::uint16_t>(pose_joints.size());
    m.pose_joints = data_or_null(pose_joints);
    m.feature_dim = feature_dim;
    m.projection_mean = data_or_null(projection_mean);
    m.projection_matrix = data_or_null(projection_matrix);
    m.component_count = component_count;
    m.covariance = covariance;
    m.gmm_means = data_or_null(gmm_means);
    m.gmm_factors = data_or_null(gmm_factors);
    m.gmm_log_normalizers = data_or_null(gmm_log_normalizers);
    m.gmm_log_weights = data_or_null(gmm_log_weights);
    m.node_count = static_cast<std::uint16_t>(node_characters.size());
    m.node_centroids = data_or_null(node_centroids);
    m.node_children = data_or_null(node_children);
    m.node_characters = data_or_null(node_characters);
    m.character_count = character_count;
    m.character_distances = data_or_null(character_distances);
    m.string_period_us = string_period_us;
    m.representative_count = static_cast<std::uint16_t>(representative_labels.size());
    m.representative_offsets = representative_offsets.data();
    m.representative_chars = data_or_null(representative_chars);
    m.representative_labels = data_or_null(representative_labels);
    m.label_count = static_cast<std::uint16_t>(label_names.size());
    m.label_names = data_or_null(label_name_pointers_);
    m.variant = variant;
    m.normalization = normalization;
    m.window_chars = window_chars;
    m.step_chars = step_chars;
    m.neighbours = neighbours;
    m.unknown_distance = unknown_distance;
    return m;
}

void set_gmm(ModelData& model, const std::vector<Eigen::VectorXd>& means,
             const std::vector<Eigen::MatrixXd>& covariances, const std::vector<double>& weights,
             Covariance kind) {
    const std::size_t J = means.size();
    if (J == 0 || covariances.size() != J || weights.size() != J)
        throw std::invalid_argument("set_gmm: means, covariances and weights differ in count");
    const Eigen::Index d = means[0].size();
    if (d == 0) throw std::invalid_argument("set_gmm: empty mean");
    const double log_2pi = std::log(2.0 * 3.14159265358979323846);
    model.component_count = static_cast<std::uint16_t>(J);
    model.covariance = kind;
    model.gmm_means.clear();
    model.gmm_factors.clear();
    model.gmm_log_normalizers.clear();
    model.gmm_log_weights.clear();
    for (std::size_t j = 0; j < J; ++j) {
        const Eigen::MatrixXd& cov = covariances[j];
        if (means[j].size() != d || cov.rows() != d || cov.cols() != d)
            throw std::invalid_argument("set_gmm: component " + std::to_string(j) + " has the wrong size");
        if (!(weights[j] > 0.0)) throw std::invalid_argument("set_gmm: weights must be positive");
        for (Eigen::Index c = 0; c < d; ++c) model.gmm_means.push_back(static_cast<float>(means[j][c]));
        double log_det_u = 0.0;
        if (kind == Covariance::diagonal) {
            for (Eigen::Index c = 0; c < d; ++c) {
                if (!(cov(c, c) > 0.0)) throw std::invalid_argument("set_gmm: non-positive variance");
                const double u = 1.0 / std::sqrt(cov(c, c));
                model.gmm_factors.push_back(static_cast<float>(u));
                log_det_u += std::log(u);
            }
        } else {
            if (!cov.isApprox(cov.transpose(), 1e-9))
                throw std::invalid_argument("set_gmm: covariance is not symmetric");
            Eigen::LLT<Eigen::MatrixXd> cov_llt(cov);
            if (cov_llt.info() != Eigen::Success)
                throw std::invalid_argument("set_gmm: covariance is not positive definite");
            const Eigen::MatrixXd precision = cov_llt.solve(Eigen::MatrixXd::Identity(d, d));
            Eigen::LLT<Eigen::MatrixXd> prec_llt(0.5 * (precision + precision.transpose()));
            if (prec_llt.info() != Eigen::Success)
                throw std::invalid_argument("set_gmm: precision is not positive definite");
            const Eigen::MatrixXd upper = prec_llt.matrixU();  // precision = Uᵀ U
            for (Eigen::Index c = 0; c < d; ++c)
                for (Eigen::Index r = 0; r <= c; ++r) model.gmm_factors.push_back(static_cast<float>(upper(r, c)));
            for (Eigen::Index c = 0; c < d; ++c) log_det_u += std::log(upper(c, c));
        }
        model.gmm_log_normalizers.push_back(static_cast<float>(-0.5 * static_cast<double>(d) * log_2pi + log_det_u));
        model.gmm_log_weights.push_back(static_cast<float>(std::log(weights[j])));
    }
    model.feature_dim = static_cast<std::uint16_t>(d);
}

void set_character_distances_from_leaves(ModelData& model) {
    const std::size_t K = model.character_count, J = model.view().tree_dim();
    std::vector<const float*> leaf(K, nullptr);
    for (std::size_t n = 0; n < model.node_characters.size(); ++n)
        if (model.node_children[2 * n] < 0) leaf.at(model.node_characters[n]) = &model.node_centroids[n * J];
    model.character_distances.assign(K * K, 0.0f);
    for (std::size_t a = 0; a < K; ++a)
        for (std::size_t b = 0; b < K; ++b) {
            if (leaf[a] == nullptr || leaf[b] == nullptr)
                throw std::invalid_argument("set_character_distances_from_leaves: a character has no leaf");
            double sum = 0.0;
            for (std::size_t j = 0; j < J; ++j) sum += std::fabs(double(leaf[a][j]) - double(leaf[b][j]));
            model.character_distances[a * K + b] = static_cast<float>(sum);
        }
}

}  // namespace host
}  // namespace actionstring
