// actionstring — stage 1: pose normalisation (design.md §1.1).
//
// Joint positions become a pose vector that does not depend on where the
// actor stands or which way they face: positions relative to the root joint,
// rotated about the up axis so the hips face a canonical direction. Optionally
// the body's size is taken out too: scaled by hip width or by the torso's bone
// lengths, or rebuilt with the model's reference bone lengths (each bone keeps
// its direction).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"

namespace actionstring {

/// Coordinates further than this from the root (metres, after scaling) are
/// treated as corrupt input rather than a pose: nothing human is 10 km wide,
/// and the bound keeps the GMM's squared distances far from float overflow.
constexpr float max_pose_coordinate = 1.0e4f;

/// The turn that takes a sensor's measured up direction to the model's up
/// axis, for a sensor pitched or rolled unlike the training one (a Kinect's
/// floor plane normal, a headset's gravity from its IMU). The facing
/// normalisation below turns about the up axis only, so without this a
/// tilted sensor is a shift the model sees (README, "Other sensors and
/// people"). `up` is in the positions' own coordinates; its length does not
/// matter. Writes a row-major 3 × 3 rotation R with R · up ∝ the up axis, the
/// smallest such turn (about up × axis).
/// An up along the axis (to within 1e-7 of a radian) gives exactly the
/// identity, which turns nothing (every coordinate keeps its bits), so
/// callers may skip it.
/// @return ok (rotation written) or invalid_argument (a null pointer, an up
///         axis beyond 2, or an up that is not finite or is shorter than
///         1e-6; rotation untouched)
inline Status up_rotation(const float* up, int up_axis, float* rotation) noexcept {
    if (up == nullptr || rotation == nullptr || up_axis < 0 || up_axis > 2) return Status::invalid_argument;
    if (!detail::is_finite(up[0]) || !detail::is_finite(up[1]) || !detail::is_finite(up[2]))
        return Status::invalid_argument;
    const float length = Eigen::Map<const Eigen::Vector3f>(up).norm();
    if (!(length >= 1.0e-6f) || !detail::is_finite(length)) return Status::invalid_argument;
    const float u[3] = {up[0] / length, up[1] / length, up[2] / length};
    const int a = up_axis, b = (up_axis + 1) % 3, c = (up_axis + 2) % 3;
    // k = u × e_a, whose only non-zero components are along b and c.
    float k[3] = {0.0f, 0.0f, 0.0f};
    k[b] = u[c];
    k[c] = -u[b];
    const float sine = std::sqrt(k[b] * k[b] + k[c] * k[c]), cosine = u[a];
    // Along the axis to float precision: nothing to turn.
    if (sine < 1.0e-7f && cosine > 0.0f) {
        for (int i = 0; i < 9; ++i) rotation[i] = i % 4 == 0 ? 1.0f : 0.0f;
        return Status::ok;
    }
    float n[3] = {0.0f, 0.0f, 0.0f};
    const bool opposite = sine < 1.0e-7f;  // upside down: half a turn about the first horizontal axis
    if (opposite) {
        n[b] = 1.0f;
    } else {
        n[b] = k[b] / sine;
        n[c] = k[c] / sine;
    }
    const float s = opposite ? 0.0f : sine, cc = opposite ? -1.0f : cosine;
    // Rodrigues: R = cos I + sin [n]× + (1 − cos) n nᵀ.
    const float cross[9] = {0.0f, -n[2], n[1], n[2], 0.0f, -n[0], -n[1], n[0], 0.0f};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            rotation[3 * i + j] = (i == j ? cc : 0.0f) + s * cross[3 * i + j] + (1.0f - cc) * n[i] * n[j];
    return Status::ok;
}

/// The canonical facing: after normalisation the horizontal hip vector
/// (right hip − left hip) points along the first horizontal axis, i.e. the
/// axis (up_axis + 1) mod 3 (z for a y-up skeleton, x for a z-up one).
///
/// @param model     the model (joint roles, up axis, pose joints, scale mode)
/// @param positions joint_count × 3 floats, xyz per joint in metres; read only
///                  during the call
/// @param pose_out  receives pose_dim() floats (caller-owned); its contents
///                  are meaningful only when the call returns Status::ok
/// @param skeleton  scratch of joint_count × 3 floats (caller-owned), needed
///                  only when the model scales by bone lengths; may be null otherwise
/// @param rotation  up_rotation()'s 3 × 3 turn, applied to every position
///                  first (about the root, which nothing else depends on);
///                  null for none
/// @param facing    receives the facing turn taken out, {cos, sin} of the
///                  horizontal hip vector's angle from the first horizontal
///                  axis (after `rotation`); null for none. Turning the pose's
///                  horizontal coordinates back by it gives the body as it
///                  faced (clip_directions() does, to turn a clip by its first
///                  facing rather than each frame by its own).
/// @return ok, non_finite_input, tracking_lost (every joint the model reads is
///         exactly at the origin, as Kinect reports lost tracking),
///         degenerate_pose (no facing direction), pose_out_of_range, or
///         invalid_argument (a null pointer the model needs)
inline Status normalize_pose(const ModelView& model, const float* input, float* pose_out, float* skeleton = nullptr,
                             const float* rotation = nullptr, float* facing = nullptr) noexcept {
    if (input == nullptr || pose_out == nullptr || model.up_axis > 2) return Status::invalid_argument;
    const bool bones = uses_bones(model.scale_mode);
    const bool tree = uses_kinematic_tree(model.scale_mode);
    if (bones && skeleton == nullptr) return Status::invalid_argument;
    // Coordinates are read and written as plain floats: under -Os the compiler
    // keeps Eigen's element-wise assignments out of line, a call per joint that
    // cost a Cortex-M4 about 5,000 instructions a frame. Lengths stay Eigen's
    // norm(), so every rounding is as before.
    auto length3 = [](const float* v) { return Eigen::Map<const Eigen::Vector3f>(v).norm(); };
    auto raw = [input](std::size_t index) { return input + 3 * index; };

    // Validate only the joints the model reads: engine rigs carry many more
    // (with bone or torso lengths, every joint: each one places its children
    // or may measure the torso). One
    // number answers both questions: the largest coordinate's bits shifted
    // left by one (the sign dropped) is 0 when every coordinate is ±0, and at
    // least 0xFF000000 (an exponent of all ones) when any is infinite or NaN.
    // A branch per coordinate cost the host about a third of the stage.
    std::uint32_t top = 0;
    auto check = [&](std::size_t index) ACTIONSTRING_DETAIL_ALWAYS_INLINE {
        const float* p = raw(index);
        for (int a = 0; a < 3; ++a) {
            const std::uint32_t twice = detail::to_bits(p[a]) << 1;
            top = twice > top ? twice : top;
        }
    };
    check(model.root_joint);
    check(model.left_hip_joint);
    check(model.right_hip_joint);
    if (tree) {
        for (std::size_t j = 0; j < model.joint_count; ++j) check(j);
    } else {
        for (std::size_t k = 0; k < model.pose_joint_count; ++k) check(model.pose_joints[k]);
    }
    if (top >= 0xFF000000u) return Status::non_finite_input;
    if (top == 0) return Status::tracking_lost;

    // Bone lengths: rebuild the skeleton root first, each joint its parent's
    // rebuilt position plus its bone's direction times the reference length.
    // A bone of (almost) no length keeps no direction and adds nothing.
    if (bones) {
        for (std::size_t k = 0; k < model.joint_count; ++k) {
            const std::size_t j = model.bone_order[k];
            float* out = skeleton + 3 * j;
            const float* at = raw(j);
            const int parent = model.joint_parents[j];
            if (parent < 0) {
                for (int a = 0; a < 3; ++a) out[a] = at[a];
                continue;
            }
            const auto p = static_cast<std::size_t>(parent);
            const float* from = raw(p);
            const float bone[3] = {at[0] - from[0], at[1] - from[1], at[2] - from[2]};
            const float length = length3(bone);
            const float* parent_out = skeleton + 3 * p;
            for (int a = 0; a < 3; ++a) out[a] = parent_out[a];
            if (length > 1.0e-6f) {
                const float stretch = model.bone_lengths[j] / length;
                for (int a = 0; a < 3; ++a) out[a] += bone[a] * stretch;
            }
        }
    }
    const float* positions = bones ? skeleton : input;
    auto joint = [positions](std::size_t index) { return positions + 3 * index; };

    const int up = model.up_axis;
    const int h1 = (up + 1) % 3;
    const int h2 = (up + 2) % 3;
    const float* root = joint(model.root_joint);
    const float* left = joint(model.left_hip_joint);
    const float* right = joint(model.right_hip_joint);
    // A turn of the sensor turns every vector between joints alike; lengths,
    // and so the size normalisations, do not change. Without one, no call
    // and no work per joint (under -Os a call per joint costs a Cortex-M4
    // hundreds of instructions a frame).
    auto turn = [rotation](float* v) {
        const float x = v[0], y = v[1], z = v[2];
        for (int i = 0; i < 3; ++i) v[i] = rotation[3 * i] * x + rotation[3 * i + 1] * y + rotation[3 * i + 2] * z;
    };
    float hips[3] = {right[0] - left[0], right[1] - left[1], right[2] - left[2]};
    if (rotation != nullptr) turn(hips);
    const float hip_width = length3(hips);
    const float horizontal = std::sqrt(hips[h1] * hips[h1] + hips[h2] * hips[h2]);
    // Hips nearly along the up axis leave the facing undefined (below ~0.06°).
    if (!(horizontal > 1.0e-6f) || !(horizontal > 1.0e-3f * hip_width)) return Status::degenerate_pose;
    const float cos_a = hips[h1] / horizontal;
    const float sin_a = hips[h2] / horizontal;
    if (facing != nullptr) facing[0] = cos_a, facing[1] = sin_a;
    float scale = model.scale_mode == ScaleMode::hip_width ? model.reference_scale / hip_width : 1.0f;
    if (model.scale_mode == ScaleMode::torso) {
        // The torso's reference length over this frame's, each summed in joint order.
        float reference = 0.0f, measured = 0.0f;
        for (std::size_t j = 0; j < model.joint_count; ++j) {
            const int parent = model.joint_parents[j];
            if (parent < 0 || !(model.bone_lengths[j] > 0.0f)) continue;
            const float* at = joint(j);
            const float* from = joint(static_cast<std::size_t>(parent));
            const float bone[3] = {at[0] - from[0], at[1] - from[1], at[2] - from[2]};
            reference += model.bone_lengths[j];
            measured += length3(bone);
        }
        // A torso of (almost) no length gives no size (validation keeps reference > 1 mm).
        if (!(measured > 1.0e-3f * reference)) return Status::degenerate_pose;
        scale = reference / measured;
    }

    // Every coordinate is written, and the range is judged once at the end
    // (pose_out means nothing unless the call returns ok).
    std::uint32_t out_of_range = 0;
    // One loop per case, so the unturned one is the loop it always was.
    auto write = [&](std::size_t k, const float* rel) ACTIONSTRING_DETAIL_ALWAYS_INLINE {
        float* out = pose_out + 3 * k;
        out[up] = rel[up];
        out[h1] = cos_a * rel[h1] + sin_a * rel[h2];
        out[h2] = -sin_a * rel[h1] + cos_a * rel[h2];
        // The negated comparison also rejects a NaN from inf − inf.
        auto outside = [](float v) { return static_cast<std::uint32_t>(!(std::fabs(v) <= max_pose_coordinate)); };
        out_of_range |= outside(out[0]) | outside(out[1]) | outside(out[2]);
    };
    if (rotation == nullptr) {
        for (std::size_t k = 0; k < model.pose_joint_count; ++k) {
            const float* at = joint(model.pose_joints[k]);
            const float rel[3] = {(at[0] - root[0]) * scale, (at[1] - root[1]) * scale, (at[2] - root[2]) * scale};
            write(k, rel);
        }
    } else {
        for (std::size_t k = 0; k < model.pose_joint_count; ++k) {
            const float* at = joint(model.pose_joints[k]);
            float rel[3] = {(at[0] - root[0]) * scale, (at[1] - root[1]) * scale, (at[2] - root[2]) * scale};
            turn(rel);
            write(k, rel);
        }
    }
    return out_of_range == 0 ? Status::ok : Status::pose_out_of_range;
}

}  // namespace actionstring
