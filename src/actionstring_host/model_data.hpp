// actionstring host library — an owning model whose view() drives the runtime.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "actionstring/model.hpp"

namespace actionstring {
namespace host {

/// Every table of a model in host memory. view() returns a ModelView pointing
/// into this object: it is valid while the object lives and is not modified.
/// Not copyable (the view's pointers would dangle); movable.
struct ModelData {
    ModelData() = default;
    ModelData(const ModelData&) = delete;
    ModelData& operator=(const ModelData&) = delete;
    ModelData(ModelData&&) = default;
    ModelData& operator=(ModelData&&) = default;

    // Skeleton and normalisation.
    std::uint16_t joint_count = 0;
    std::uint16_t root_joint = 0, left_hip_joint = 0, right_hip_joint = 0;
    std::uint8_t up_axis = 1;
    ScaleMode scale_mode = ScaleMode::none;
    float reference_scale = 1.0f;
    std::vector<std::uint16_t> pose_joints;
    // Projection (empty: none).
    std::uint16_t feature_dim = 0;
    std::vector<float> projection_mean, projection_matrix;
    // GMM.
    std::uint16_t component_count = 0;
    Covariance covariance = Covariance::full;
    std::vector<float> gmm_means, gmm_factors, gmm_log_normalizers, gmm_log_weights;
    // Tree and W.
    std::vector<float> node_centroids;
    std::vector<std::int16_t> node_children;
    std::vector<Character> node_characters;
    std::uint16_t character_count = 0;
    std::vector<float> character_distances;
    // Strings.
    std::uint32_t string_period_us = 0;
    std::vector<std::uint32_t> representative_offsets{0};
    std::vector<Character> representative_chars;
    std::vector<LabelId> representative_labels;
    std::vector<std::string> label_names;
    // Matching.
    MatchVariant variant = MatchVariant::whole;
    LengthNormalization normalization = LengthNormalization::none;
    std::uint16_t window_chars = 0, step_chars = 0, neighbours = 1;
    float unknown_distance = detail::infinity();

    /// Appends one representative string with its label.
    void add_representative(const std::vector<Character>& chars, LabelId label);

    /// Non-owning view; rebuilds the label-name pointer table, hence non-const.
    ModelView view();

private:
    std::vector<const char*> label_name_pointers_;
};

/// Fills the GMM tables from means, covariances and weights given in double.
/// Factors come from the Cholesky factor of each precision; log-normalisers
/// and log-weights are precomputed, so the runtime never inverts anything.
/// Diagonal covariance reads only each covariance's diagonal.
/// Throws std::invalid_argument on size mismatch, a non-positive weight, or a
/// covariance that is not symmetric positive definite.
void set_gmm(ModelData& model, const std::vector<Eigen::VectorXd>& means,
             const std::vector<Eigen::MatrixXd>& covariances, const std::vector<double>& weights,
             Covariance kind);

/// W[a][b] = L1 distance between the leaf centroids of characters a and b.
void set_character_distances_from_leaves(ModelData& model);

}  // namespace host
}  // namespace actionstring
