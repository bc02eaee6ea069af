// actionstring host library — a small synthetic world for demos and tests.
//
// A 5-joint skeleton (pelvis, hips, hands), a handful of hand key-poses, and
// actions that move through them. Until a trainer exists, its model is built
// directly from the key-poses: one GMM component per key-pose, a balanced
// tree over the components, and each action's clean string as its
// representative. It exercises every runtime stage on data whose right
// answer is known by construction; it says nothing about accuracy on real motion.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/clip.hpp"
#include "io/clip_list.hpp"
#include "model/model_data.hpp"

namespace actionstring {
namespace host {

/// One synthetic action: key-poses visited in order, each held then blended to the next.
struct ToyAction {
    std::string name;
    std::vector<int> key_poses;
    double seconds_per_pose = 0.4;
    double duration() const { return seconds_per_pose * static_cast<double>(key_poses.size()); }
};

/// One frame of a synthetic stream.
struct ToyFrame {
    std::int64_t time_us = 0;
    std::vector<float> positions;  ///< 5 joints × xyz, metres, y up.
    int action = -1;               ///< Index of the action being performed.
};

/// Settings of the toy world's model.
struct ToyOptions {
    Covariance covariance = Covariance::full;
    MatchVariant variant = MatchVariant::whole;
    LengthNormalization normalization = LengthNormalization::path;
    double string_rate_hz = 10.0;
    double window_seconds = 2.0;
    double step_seconds = 0.5;
    std::uint16_t neighbours = 1;
};

/// Key-poses, actions and the model built from them.
struct ToyWorld {
    static constexpr int joint_count = 5;
    std::vector<std::vector<float>> key_poses;  ///< Each 5 × xyz, canonical frame, root at origin.
    std::vector<ToyAction> actions;
    ModelData model;
};

/// The toy skeleton's joints: root, lhipjoint, rhipjoint, lhand, rhand.
std::vector<std::string> toy_joint_names();

/// Builds the world; deterministic.
ToyWorld make_toy_world(const ToyOptions& options = {});

/// Stream settings for toy_stream().
struct ToyStreamOptions {
    double frame_rate_hz = 30.0;
    double position_noise_m = 0.01;  ///< Gaussian noise per coordinate.
    double frame_time_jitter = 0.0;  ///< Fraction of a frame period, uniform ±.
    double drop_probability = 0.0;   ///< Chance that a frame is missing.
    std::uint32_t seed = 1;
};

/// Performs `sequence` (action indices) back to back, each at a random place,
/// facing and hip width, and samples it at the frame rate.
std::vector<ToyFrame> toy_stream(const ToyWorld& world, const std::vector<int>& sequence,
                                 const ToyStreamOptions& options = {});

/// A synthetic stream as a clip (joints: root, lhipjoint, rhipjoint, lhand, rhand).
Clip toy_clip(const std::vector<ToyFrame>& frames, const std::string& source);

/// `performances` labelled clips of every action, each at its own place,
/// facing, size and noise (seeded), for training and evaluation tests.
std::vector<LabelledClip> toy_clips(const ToyWorld& world, int performances, std::uint32_t seed,
                                    double frame_rate_hz = 60.0);

}  // namespace host
}  // namespace actionstring
