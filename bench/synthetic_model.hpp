// A random model of any size, for measuring cost and memory (not accuracy).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "model/model_data.hpp"

namespace bench {

struct ModelSize {
    int joints = 31;           ///< HDM05/CMU ASF skeleton
    int feature_dim = 24;      ///< d after PCA (0: no PCA)
    int components = 40;       ///< J
    int characters = 64;       ///< K (tree leaves)
    int representatives = 30;  ///< R
    int representative_length = 30;
    double string_rate_hz = 12.0;
    double window_seconds = 2.0;
    double step_seconds = 0.5;
    actionstring::Covariance covariance = actionstring::Covariance::full;
    int exemplars_per_label = 0;  ///< random centres per label (10 labels), weighed by the segmenter too
    int exemplar_dims = 0;        ///< the feature's leading coordinates the centres keep (0: all d)
};

// Balanced tree with `leaves` leaves and random probability-vector centroids.
inline int add_random_node(actionstring::host::ModelData& m, std::mt19937& rng, int leaves, int& next_char) {
    const int J = m.component_count;
    const int node = static_cast<int>(m.node_characters.size());
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    float total = 0;
    std::vector<float> centroid(static_cast<std::size_t>(J));
    for (auto& c : centroid) total += (c = unit(rng) * unit(rng) * unit(rng));
    for (auto& c : centroid) m.node_centroids.push_back(c / total);
    m.node_children.push_back(-1);
    m.node_children.push_back(-1);
    m.node_characters.push_back(0);
    if (leaves == 1) {
        m.node_characters[static_cast<std::size_t>(node)] = static_cast<actionstring::Character>(next_char++);
        return node;
    }
    const int left = add_random_node(m, rng, leaves / 2, next_char);
    const int right = add_random_node(m, rng, leaves - leaves / 2, next_char);
    m.node_children[2 * static_cast<std::size_t>(node)] = static_cast<std::int16_t>(left);
    m.node_children[2 * static_cast<std::size_t>(node) + 1] = static_cast<std::int16_t>(right);
    return node;
}

inline void make_random_model(actionstring::host::ModelData& m, const ModelSize& size, std::uint32_t seed = 1) {
    using namespace actionstring;
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    m.joint_count = static_cast<std::uint16_t>(size.joints);
    m.root_joint = 0;
    m.left_hip_joint = 1;
    m.right_hip_joint = 2;
    m.up_axis = 1;
    for (int j = 1; j < size.joints; ++j) m.pose_joints.push_back(static_cast<std::uint16_t>(j));
    const int D = 3 * (size.joints - 1);
    const int d = size.feature_dim > 0 ? size.feature_dim : D;
    if (size.feature_dim > 0) {
        m.projection_mean.assign(static_cast<std::size_t>(D), 0.0f);
        for (int i = 0; i < d * D; ++i)
            m.projection_matrix.push_back(static_cast<float>(normal(rng) / std::sqrt(static_cast<double>(D))));
    }
    std::vector<Eigen::VectorXd> means;
    std::vector<Eigen::MatrixXd> covs;
    std::vector<double> weights;
    for (int j = 0; j < size.components; ++j) {
        Eigen::VectorXd mean(d);
        for (int i = 0; i < d; ++i) mean[i] = 0.3 * normal(rng);
        Eigen::MatrixXd a(d, d);
        for (Eigen::Index i = 0; i < a.size(); ++i) a(i) = 0.05 * normal(rng);
        means.push_back(mean);
        covs.push_back(a * a.transpose() + 0.01 * Eigen::MatrixXd::Identity(d, d));
        weights.push_back(1.0 / size.components);
    }
    host::set_gmm(m, means, covs, weights, size.covariance);
    m.character_count = static_cast<std::uint16_t>(size.characters);
    int next_char = 0;
    add_random_node(m, rng, size.characters, next_char);
    host::set_character_distances_from_leaves(m);
    m.string_period_us = static_cast<std::uint32_t>(std::lround(1e6 / size.string_rate_hz));
    std::uniform_int_distribution<int> pick(0, size.characters - 1);
    for (int r = 0; r < size.representatives; ++r) {
        std::vector<Character> chars;
        for (int i = 0; i < size.representative_length; ++i) chars.push_back(static_cast<Character>(pick(rng)));
        m.add_representative(chars, static_cast<LabelId>(r % 10));
    }
    for (int l = 0; l < 10; ++l) m.label_names.push_back("action" + std::to_string(l));
    m.variant = MatchVariant::whole;
    m.normalization = LengthNormalization::path;
    m.window_chars = static_cast<std::uint16_t>(std::lround(size.window_seconds * size.string_rate_hz));
    m.step_chars = static_cast<std::uint16_t>(std::lround(size.step_seconds * size.string_rate_hz));
    m.neighbours = 1;
    if (size.exemplars_per_label > 0) {
        std::normal_distribution<float> centre(0.0f, 0.3f);
        const int kept = size.exemplar_dims > 0 && size.exemplar_dims < d ? size.exemplar_dims : d;
        m.exemplar_dim = static_cast<std::uint16_t>(kept < d ? kept : 0);
        for (int l = 0; l < 10; ++l)
            for (int e = 0; e < size.exemplars_per_label; ++e) {
                m.exemplar_labels.push_back(static_cast<LabelId>(l));
                for (int i = 0; i < kept; ++i) m.exemplars.push_back(centre(rng));
            }
        m.exemplar_weight = 1.0f;
        m.exemplar_scale = 1.0f;
        m.segment_exemplar_weight = 0.1f;
    }
}

/// A skeleton jittering around a standing pose, joint_count × xyz per frame.
inline std::vector<std::vector<float>> random_walk_frames(int joints, int count, std::uint32_t seed = 2) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> step(0.0f, 0.01f);
    std::vector<float> pose(static_cast<std::size_t>(3 * joints));
    for (int j = 0; j < joints; ++j) {
        pose[static_cast<std::size_t>(3 * j)] = 0.05f * static_cast<float>(j % 5);
        pose[static_cast<std::size_t>(3 * j + 1)] = 1.0f + 0.05f * static_cast<float>(j % 7);
        pose[static_cast<std::size_t>(3 * j + 2)] = 0.03f * static_cast<float>(j % 3);
    }
    pose[5] = -0.1f;  // left hip
    pose[8] = 0.1f;   // right hip
    std::vector<std::vector<float>> frames;
    for (int f = 0; f < count; ++f) {
        for (std::size_t i = 9; i < pose.size(); ++i) pose[i] += step(rng);
        frames.push_back(pose);
    }
    return frames;
}

}  // namespace bench
