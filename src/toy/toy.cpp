#include "toy/toy.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "actionstring/encoder.hpp"
#include "run/state.hpp"

namespace actionstring {
namespace host {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Hands relative to the pelvis in the canonical frame (y up, right hip on +z).
std::vector<float> key_pose(float lx, float ly, float lz, float rx, float ry, float rz) {
    return {0, 0, 0, 0, 0, -0.1f, 0, 0, 0.1f, lx, ly, lz, rx, ry, rz};
}

// Balanced tree over the components: node centroids are the mean of their
// leaves' one-hot centroids, so descent of a near one-hot posterior reaches
// the component's own leaf.
int build_tree(ModelData& m, int first, int count) {
    const int J = m.component_count;
    const int node = static_cast<int>(m.node_characters.size());
    m.node_characters.push_back(0);
    m.node_children.push_back(-1);
    m.node_children.push_back(-1);
    for (int j = 0; j < J; ++j)
        m.node_centroids.push_back(j >= first && j < first + count ? 1.0f / static_cast<float>(count) : 0.0f);
    if (count == 1) {
        m.node_characters[static_cast<std::size_t>(node)] = static_cast<Character>(first);
        return node;
    }
    const int half = count / 2;
    const int left = build_tree(m, first, half);
    const int right = build_tree(m, first + half, count - half);
    m.node_children[2 * static_cast<std::size_t>(node)] = static_cast<std::int16_t>(left);
    m.node_children[2 * static_cast<std::size_t>(node) + 1] = static_cast<std::int16_t>(right);
    return node;
}

Eigen::Vector3d rotate_about_y(const Eigen::Vector3d& p, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * p.x() + s * p.z(), p.y(), -s * p.x() + c * p.z()};
}

// Pose of an action at time t since its start: hold each key-pose for the
// first 60 % of its slot, then blend linearly to the next.
std::vector<float> action_pose(const ToyWorld& world, const ToyAction& action, double t) {
    const double slot =
        std::clamp(t / action.seconds_per_pose, 0.0, static_cast<double>(action.key_poses.size()) - 1e-9);
    const auto index = static_cast<std::size_t>(slot);
    const double phase = slot - static_cast<double>(index);
    const auto& a = world.key_poses[static_cast<std::size_t>(action.key_poses[index])];
    const auto& b =
        world.key_poses[static_cast<std::size_t>(action.key_poses[std::min(index + 1, action.key_poses.size() - 1)])];
    const double blend = phase < 0.6 ? 0.0 : (phase - 0.6) / 0.4;
    std::vector<float> pose(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) pose[i] = static_cast<float>((1.0 - blend) * a[i] + blend * b[i]);
    return pose;
}

}  // namespace

std::vector<std::string> toy_joint_names() { return {"root", "lhipjoint", "rhipjoint", "lhand", "rhand"}; }

ToyWorld make_toy_world(const ToyOptions& options) {
    ToyWorld world;
    world.key_poses = {
        key_pose(0.05f, 0.0f, -0.25f, 0.05f, 0.0f, 0.25f),    // 0 rest
        key_pose(0.45f, 0.35f, -0.15f, 0.45f, 0.35f, 0.15f),  // 1 both hands forward
        key_pose(0.0f, 0.95f, -0.2f, 0.0f, 0.95f, 0.2f),      // 2 both hands up
        key_pose(0.0f, 0.95f, -0.2f, 0.05f, 0.0f, 0.25f),     // 3 left hand up
        key_pose(0.05f, 0.0f, -0.25f, 0.0f, 0.95f, 0.2f),     // 4 right hand up
        key_pose(0.0f, 0.5f, -0.75f, 0.0f, 0.5f, 0.75f),      // 5 arms spread
    };
    world.actions = {
        {"raise_both", {0, 1, 2, 2, 1, 0}, 0.4},
        {"wave_left", {0, 3, 0, 3, 0}, 0.45},
        {"wave_right", {0, 4, 0, 4, 0}, 0.45},
        {"spread", {0, 5, 5, 0, 5, 0}, 0.4},
    };

    ModelData& m = world.model;
    m.joint_count = ToyWorld::joint_count;
    const std::vector<std::string> joints = toy_joint_names();
    m.joint_names.assign(joints.begin(), joints.end());
    m.root_joint = 0;
    m.left_hip_joint = 1;
    m.right_hip_joint = 2;
    m.up_axis = 1;
    m.pose_joints = {1, 2, 3, 4};
    const Eigen::Index d = 12;

    std::vector<Eigen::VectorXd> means;
    std::vector<Eigen::MatrixXd> covariances;
    std::vector<double> weights;
    std::mt19937 rng(7);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (const auto& pose : world.key_poses) {
        Eigen::VectorXd mean(d);
        for (Eigen::Index i = 0; i < d; ++i) mean[i] = pose[static_cast<std::size_t>(i) + 3];
        Eigen::MatrixXd mix(d, d);
        for (Eigen::Index i = 0; i < mix.size(); ++i) mix(i) = 0.02 * normal(rng);
        Eigen::MatrixXd cov = Eigen::MatrixXd::Identity(d, d) * (0.06 * 0.06) + mix * mix.transpose();
        means.push_back(mean);
        covariances.push_back(cov);
        weights.push_back(1.0 / static_cast<double>(world.key_poses.size()));
    }
    set_gmm(m, means, covariances, weights, options.covariance);

    m.character_count = m.component_count;
    build_tree(m, 0, m.component_count);
    set_character_distances_from_leaves(m);

    m.string_period_us = static_cast<std::uint32_t>(std::lround(1e6 / options.string_rate_hz));
    m.variant = options.variant;
    m.normalization = options.normalization;
    m.window_chars = static_cast<std::uint16_t>(std::lround(options.window_seconds * options.string_rate_hz));
    m.step_chars = static_cast<std::uint16_t>(std::lround(options.step_seconds * options.string_rate_hz));
    m.neighbours = options.neighbours;
    for (const auto& action : world.actions) m.label_names.push_back(action.name);

    // Representatives: each action's string from a clean performance, through
    // the runtime's own encoder.
    ModelView view = m.view();
    for (std::size_t a = 0; a < world.actions.size(); ++a) {
        Stateful<StringEncoder> encoder;
        if (encoder.init(view, EncoderConfig{1000000, 0}) != Status::ok)
            throw std::logic_error("toy model rejected by the encoder");
        ToyStreamOptions clean;
        clean.position_noise_m = 0.0;
        clean.frame_rate_hz = 60.0;
        std::vector<Character> chars;
        for (const auto& frame : toy_stream(world, {static_cast<int>(a)}, clean)) {
            const EncodedFrame e = encoder->push_frame(frame.time_us, frame.positions.data());
            chars.insert(chars.end(), e.from_previous, e.previous);
            chars.insert(chars.end(), e.from_current, e.current);
        }
        m.add_representative(chars, static_cast<LabelId>(a));
    }
    return world;
}

std::vector<ToyFrame> toy_stream(const ToyWorld& world, const std::vector<int>& sequence,
                                 const ToyStreamOptions& options) {
    if (!(options.frame_rate_hz > 0.0)) throw std::invalid_argument("toy_stream: frame rate must be positive");
    std::mt19937 rng(options.seed);
    std::normal_distribution<double> noise(0.0, options.position_noise_m > 0 ? options.position_noise_m : 1.0);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double frame_period = 1.0 / options.frame_rate_hz;
    std::vector<ToyFrame> frames;
    double start = 0.0;
    std::int64_t last_time = -1;
    for (const int index : sequence) {
        const ToyAction& action = world.actions.at(static_cast<std::size_t>(index));
        const double facing = 2.0 * kPi * unit(rng);
        const double scale = 0.85 + 0.3 * unit(rng);
        const Eigen::Vector3d place(4.0 * unit(rng) - 2.0, 0.9 + 0.1 * unit(rng), 4.0 * unit(rng) - 2.0);
        const double duration = action.duration();
        const auto first = static_cast<long>(std::ceil(start / frame_period - 1e-9));
        for (long f = first; static_cast<double>(f) * frame_period < start + duration; ++f) {
            double t = static_cast<double>(f) * frame_period;
            if (options.frame_time_jitter > 0.0)
                t += (2.0 * unit(rng) - 1.0) * options.frame_time_jitter * frame_period;
            if (options.drop_probability > 0.0 && unit(rng) < options.drop_probability) continue;
            ToyFrame frame;
            frame.time_us = std::max<std::int64_t>(last_time, std::llround(t * 1e6));
            last_time = frame.time_us;
            frame.action = index;
            const std::vector<float> pose = action_pose(world, action, t - start);
            for (int j = 0; j < ToyWorld::joint_count; ++j) {
                const auto base = static_cast<std::size_t>(3 * j);
                Eigen::Vector3d p(pose[base], pose[base + 1], pose[base + 2]);
                p = rotate_about_y(p * scale, facing) + place;
                for (int a = 0; a < 3; ++a) {
                    const double n = options.position_noise_m > 0 ? noise(rng) : 0.0;
                    frame.positions.push_back(static_cast<float>(p[a] + n));
                }
            }
            frames.push_back(std::move(frame));
        }
        start += duration;
    }
    return frames;
}

Clip toy_clip(const std::vector<ToyFrame>& frames, const std::string& source) {
    Clip clip;
    clip.source = source;
    clip.joint_names = toy_joint_names();
    clip.parents = {-1, 0, 0, 0, 0};
    for (const ToyFrame& frame : frames) {
        clip.times.push_back(static_cast<double>(frame.time_us) * 1e-6);
        clip.positions.insert(clip.positions.end(), frame.positions.begin(), frame.positions.end());
    }
    flag_lost_frames(clip);
    assign_roles(clip, {});
    return clip;
}

std::vector<LabelledClip> toy_clips(const ToyWorld& world, int performances, std::uint32_t seed, double frame_rate_hz) {
    std::vector<LabelledClip> clips;
    for (int p = 0; p < performances; ++p)
        for (std::size_t a = 0; a < world.actions.size(); ++a) {
            ToyStreamOptions options;
            options.seed = seed + static_cast<std::uint32_t>(p * 97 + static_cast<int>(a));
            options.frame_rate_hz = frame_rate_hz;
            options.position_noise_m = 0.015;
            options.frame_time_jitter = 0.2;
            const std::string name = world.actions[a].name + "_" + std::to_string(p);
            clips.push_back({toy_clip(toy_stream(world, {static_cast<int>(a)}, options), name), world.actions[a].name,
                             "toy" + std::to_string(p)});
        }
    return clips;
}

}  // namespace host
}  // namespace actionstring
