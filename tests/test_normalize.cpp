// Pose normalisation: invariance to position and facing, and rejected frames.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "actionstring/gmm.hpp"
#include "actionstring/normalize.hpp"
#include "model/artifact.hpp"
#include "toy/toy.hpp"
#include "train/pipeline.hpp"

using namespace actionstring;

namespace {

// Rewrites a y-up pose so that `up` is the vertical axis (cyclic relabelling).
std::vector<float> with_up_axis(const std::vector<float>& y_up, int up) {
    std::vector<float> out(y_up.size());
    for (std::size_t j = 0; j < y_up.size() / 3; ++j)
        for (int a = 0; a < 3; ++a)
            out[3 * j + static_cast<std::size_t>((a + up + 2) % 3)] = y_up[3 * j + static_cast<std::size_t>(a)];
    return out;
}

std::vector<float> transform(const std::vector<float>& pose, const Eigen::Matrix3f& rotation,
                             const Eigen::Vector3f& shift, float scale = 1.0f) {
    std::vector<float> out(pose.size());
    for (std::size_t j = 0; j < pose.size() / 3; ++j) {
        const Eigen::Vector3f p(pose[3 * j], pose[3 * j + 1], pose[3 * j + 2]);
        const Eigen::Vector3f q = rotation * (p * scale) + shift;
        for (int a = 0; a < 3; ++a) out[3 * j + static_cast<std::size_t>(a)] = q[a];
    }
    return out;
}

std::vector<float> normalized(const ModelView& view, const std::vector<float>& pose, Status expect = Status::ok) {
    std::vector<float> out(view.pose_dim(), -1.0f);
    CHECK(normalize_pose(view, pose.data(), out.data()) == expect);
    return out;
}

double max_difference(const std::vector<float>& a, const std::vector<float>& b) {
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        worst = std::max(worst, std::fabs(static_cast<double>(a[i]) - static_cast<double>(b[i])));
    return worst;
}

// A model without a GMM (PCA 6) trained on `clips` with this size normalisation.
host::ModelData scaled_model(const std::vector<host::LabelledClip>& clips, ScaleMode mode) {
    host::TrainingOptions options;
    options.scale_mode = mode;
    options.components = 0;
    options.pca_dim = 6;
    return host::train_model(clips, options);
}

}  // namespace

TEST_CASE("translation and rotation about the up axis leave the pose and feature unchanged") {
    host::ToyWorld world = host::make_toy_world();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> angle(-3.14159f, 3.14159f), offset(-5.0f, 5.0f);
    for (int up = 0; up < 3; ++up) {
        world.model.up_axis = static_cast<std::uint8_t>(up);
        const ModelView view = world.model.view();
        Eigen::Vector3f up_vector = Eigen::Vector3f::Zero();
        up_vector[up] = 1.0f;
        for (const auto& key : world.key_poses) {
            const std::vector<float> base = with_up_axis(key, up);
            const std::vector<float> reference = normalized(view, base);
            std::vector<float> ref_posterior(view.component_count), posterior(view.component_count),
                scratch(gmm_scratch_floats(view));
            const bool projected_identity = !view.has_projection();
            REQUIRE(projected_identity);
            REQUIRE(gmm_posterior(view, reference.data(), ref_posterior.data(), scratch.data()) == Status::ok);
            for (int trial = 0; trial < 25; ++trial) {
                const Eigen::Matrix3f rotation = Eigen::AngleAxisf(angle(rng), up_vector).toRotationMatrix();
                const Eigen::Vector3f shift(offset(rng), offset(rng), offset(rng));
                const std::vector<float> moved = normalized(view, transform(base, rotation, shift));
                CHECK(max_difference(moved, reference) < 2e-5);
                REQUIRE(gmm_posterior(view, moved.data(), posterior.data(), scratch.data()) == Status::ok);
                CHECK(max_difference(posterior, ref_posterior) < 1e-4);
            }
            // A tilt about the horizontal axis across the hips' line is not a change
            // of facing: the pose must change.
            Eigen::Vector3f horizontal = Eigen::Vector3f::Zero();
            horizontal[(up + 2) % 3] = 1.0f;
            const Eigen::Matrix3f tilt = Eigen::AngleAxisf(0.5f, horizontal).toRotationMatrix();
            CHECK(max_difference(normalized(view, transform(base, tilt, Eigen::Vector3f::Zero())), reference) > 0.05);
        }
    }
}

TEST_CASE("up_rotation turns the sensor's up onto the model's axis, the smallest turn, and refuses bad ones") {
    std::mt19937 rng(11);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    for (int up = 0; up < 3; ++up) {
        Eigen::Vector3f axis = Eigen::Vector3f::Zero();
        axis[up] = 1.0f;
        Eigen::Vector3f aside = Eigen::Vector3f::Zero();
        aside[(up + 1) % 3] = 1e-8f;  // along the axis to float precision, either way up
        std::vector<Eigen::Vector3f> ups = {-axis,        2.5f * axis,   Eigen::Vector3f(0.3f, 0.2f, 0.1f),
                                            axis + aside, -axis + aside, axis + 1e-4f * aside.normalized()};
        for (int trial = 0; trial < 50; ++trial) ups.emplace_back(normal(rng), normal(rng), normal(rng));
        for (const Eigen::Vector3f& u : ups) {
            CAPTURE(up);
            CAPTURE(u.transpose());
            float r[9] = {};
            REQUIRE(up_rotation(u.data(), up, r) == Status::ok);
            const Eigen::Matrix3f R = Eigen::Map<const Eigen::Matrix<float, 3, 3, Eigen::RowMajor>>(r);
            CHECK((R * u.normalized() - axis).norm() < 1e-5f);
            CHECK((R.transpose() * R - Eigen::Matrix3f::Identity()).norm() < 1e-5f);
            CHECK(R.determinant() == doctest::Approx(1.0).epsilon(1e-5));
            // The smallest turn: the line across both (up × axis) stays where it is.
            const Eigen::Vector3f line = u.cross(axis);
            if (line.norm() > 1e-3f) CHECK((R * line - line).norm() < 1e-5f * line.norm());
        }
        // Along the axis already: exactly the identity, which turns no coordinate's bits.
        float r[9] = {};
        const Eigen::Vector3f along = 3.0f * axis;
        REQUIRE(up_rotation(along.data(), up, r) == Status::ok);
        for (int i = 0; i < 9; ++i) CHECK(r[i] == (i % 4 == 0 ? 1.0f : 0.0f));
    }
    float r[9] = {};
    const float zero[3] = {0.0f, 0.0f, 0.0f}, tiny[3] = {1e-7f, 0.0f, 0.0f},
                nan[3] = {0.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f}, huge[3] = {3e38f, 3e38f, 0.0f},
                fine[3] = {0.0f, 1.0f, 0.1f};
    CHECK(up_rotation(zero, 1, r) == Status::invalid_argument);
    CHECK(up_rotation(tiny, 1, r) == Status::invalid_argument);
    CHECK(up_rotation(nan, 1, r) == Status::invalid_argument);
    CHECK(up_rotation(huge, 1, r) == Status::invalid_argument);  // its length overflows float
    CHECK(up_rotation(fine, 3, r) == Status::invalid_argument);
    CHECK(up_rotation(nullptr, 1, r) == Status::invalid_argument);
    CHECK(up_rotation(fine, 1, nullptr) == Status::invalid_argument);
}

TEST_CASE("a sensor tilted any way gives the upright pose when its up direction is given") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> angle(-0.6f, 0.6f), direction(-1.0f, 1.0f);
    for (const auto& key : world.key_poses) {
        const std::vector<float> reference = normalized(view, key);
        for (int trial = 0; trial < 20; ++trial) {
            // A sensor pitched and rolled (up to about 35°) and turned about the up axis, somewhere else.
            const Eigen::Vector3f line = Eigen::Vector3f(direction(rng), direction(rng), direction(rng)).normalized();
            const Eigen::Matrix3f sensor = Eigen::AngleAxisf(angle(rng), line).toRotationMatrix() *
                                           Eigen::AngleAxisf(3.0f * angle(rng), Eigen::Vector3f::UnitY());
            const std::vector<float> seen = transform(key, sensor, Eigen::Vector3f(0.5f, 1.0f, 2.5f));
            const Eigen::Vector3f up = sensor * Eigen::Vector3f::UnitY() * 9.81f;  // gravity's length does not matter
            float r[9] = {};
            REQUIRE(up_rotation(up.data(), view.up_axis, r) == Status::ok);
            std::vector<float> turned(view.pose_dim());
            REQUIRE(normalize_pose(view, seen.data(), turned.data(), nullptr, r) == Status::ok);
            CHECK(max_difference(turned, reference) < 2e-5);
        }
        // Without it, a sensor pitched by 0.5 rad is a shift the pose shows.
        const Eigen::Matrix3f pitched = Eigen::AngleAxisf(0.5f, Eigen::Vector3f::UnitX()).toRotationMatrix();
        const std::vector<float> seen = transform(key, pitched, Eigen::Vector3f::Zero());
        CHECK(max_difference(normalized(view, seen), reference) > 0.05);
        const Eigen::Vector3f up = pitched * Eigen::Vector3f::UnitY();
        float r[9] = {};
        REQUIRE(up_rotation(up.data(), view.up_axis, r) == Status::ok);
        std::vector<float> turned(view.pose_dim());
        REQUIRE(normalize_pose(view, seen.data(), turned.data(), nullptr, r) == Status::ok);
        CHECK(max_difference(turned, reference) < 2e-5);
        // The identity turns nothing: the same bits as no rotation.
        float identity[9];
        const float upright[3] = {0.0f, 1.0f, 0.0f};
        REQUIRE(up_rotation(upright, view.up_axis, identity) == Status::ok);
        std::vector<float> same(view.pose_dim());
        REQUIRE(normalize_pose(view, key.data(), same.data(), nullptr, identity) == Status::ok);
        CHECK(same == reference);
    }
}

TEST_CASE("the hips face the canonical direction after normalisation") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    const Eigen::Matrix3f turn = Eigen::AngleAxisf(2.0f, Eigen::Vector3f::UnitY()).toRotationMatrix();
    const std::vector<float> pose = normalized(view, transform(world.key_poses[0], turn, {1, 2, 3}));
    // Pose joints 1, 2 are the hips: right − left points along +z (axis (1 + 1) mod 3).
    CHECK(pose[5] - pose[2] == doctest::Approx(0.2).epsilon(1e-4));
    CHECK(pose[3] - pose[0] == doctest::Approx(0.0).scale(1.0).epsilon(1e-5));
}

TEST_CASE("hip-width scaling maps actors of different size together") {
    host::ToyWorld world = host::make_toy_world();
    world.model.scale_mode = ScaleMode::hip_width;
    world.model.reference_scale = 0.2f;
    const ModelView view = world.model.view();
    const std::vector<float> reference = normalized(view, world.key_poses[2]);
    const std::vector<float> tall =
        normalized(view, transform(world.key_poses[2], Eigen::Matrix3f::Identity(), {0, 1, 0}, 1.3f));
    CHECK(max_difference(reference, tall) < 1e-5);
    world.model.scale_mode = ScaleMode::none;
    const ModelView unscaled = world.model.view();
    CHECK(max_difference(
              normalized(unscaled, world.key_poses[2]),
              normalized(unscaled, transform(world.key_poses[2], Eigen::Matrix3f::Identity(), {0, 1, 0}, 1.3f))) > 0.1);
}

TEST_CASE("frames that are not poses are rejected with a reason") {
    host::ToyWorld world = host::make_toy_world();
    const ModelView view = world.model.view();
    std::vector<float> pose = transform(world.key_poses[1], Eigen::Matrix3f::Identity(), {1, 1, 1});
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();

    auto with = [&](std::size_t index, float value) {
        std::vector<float> p = pose;
        p[index] = value;
        return p;
    };
    normalized(view, with(10, nan), Status::non_finite_input);
    normalized(view, with(0, inf), Status::non_finite_input);
    normalized(view, with(13, -inf), Status::non_finite_input);
    normalized(view, std::vector<float>(15, 0.0f), Status::tracking_lost);
    // The edges of the one-number check (normalize.hpp): a NaN with its sign bit
    // set, the largest finite float (a pose, out of range), negative zeros (no
    // tracking), and a NaN among zeros (not a pose rather than lost tracking).
    normalized(view, with(10, -nan), Status::non_finite_input);
    normalized(view, with(9, std::numeric_limits<float>::max()), Status::pose_out_of_range);
    normalized(view, with(9, -std::numeric_limits<float>::max()), Status::pose_out_of_range);
    normalized(view, std::vector<float>(15, -0.0f), Status::tracking_lost);
    std::vector<float> zeros_and_nan(15, 0.0f);
    zeros_and_nan[14] = nan;
    normalized(view, zeros_and_nan, Status::non_finite_input);
    normalized(view, with(9, 3.0e4f), Status::pose_out_of_range);
    normalized(view, with(9, 3.0e38f), Status::pose_out_of_range);
    // Hips on the vertical line through each other: no facing.
    std::vector<float> vertical = pose;
    vertical[3] = vertical[6] = 1.0f;
    vertical[5] = vertical[8] = 1.0f;
    vertical[4] = 1.0f;
    vertical[7] = 1.2f;
    normalized(view, vertical, Status::degenerate_pose);
    CHECK(normalize_pose(view, nullptr, pose.data()) == Status::invalid_argument);
}

TEST_CASE("torso scaling: a bigger body gives the same pose, its own proportions kept") {
    const std::vector<host::LabelledClip> clips = host::toy_clips(host::make_toy_world(), 2, 4);
    const host::ModelData model = scaled_model(clips, ScaleMode::torso);
    const ModelView view = model.view();
    REQUIRE(view.scale_mode == ScaleMode::torso);
    REQUIRE_FALSE(uses_bones(view.scale_mode));  // no scratch skeleton needed
    REQUIRE(uses_kinematic_tree(view.scale_mode));
    CHECK(view.bone_lengths[0] == 0.0f);  // the root has no bone
    CHECK(view.bone_lengths[1] > 0.05f);  // root → left hip, a torso bone

    const host::Clip& clip = clips.front().clip;
    const std::size_t J = clip.joint_count(), D = view.pose_dim();
    std::vector<float> pose(D), other(D);
    for (std::size_t f = 0; f < clip.frame_count(); f += 7) {
        const float* p = clip.frame(f);
        REQUIRE(normalize_pose(view, p, pose.data()) == Status::ok);
        // A person 1.3× or 0.7× the size, standing elsewhere: the same pose.
        for (const float size : {1.3f, 0.7f}) {
            std::vector<float> q(p, p + 3 * J);
            for (std::size_t j = 0; j < J; ++j)
                for (std::size_t a = 0; a < 3; ++a) q[3 * j + a] = 2.0f + p[a] + size * (p[3 * j + a] - p[a]);
            REQUIRE(normalize_pose(view, q.data(), other.data()) == Status::ok);
            for (std::size_t k = 0; k < D; ++k) CHECK(other[k] == doctest::Approx(pose[k]).epsilon(1e-5));
        }
        // Unlike bone lengths, one factor for the whole body: hips twice as wide
        // (a torso bone) shrink the whole pose, so it is not the same.
        std::vector<float> wide(p, p + 3 * J);
        for (std::size_t j = 1; j <= 2; ++j)
            for (std::size_t a = 0; a < 3; ++a) wide[3 * j + a] = p[a] + 2.0f * (p[3 * j + a] - p[a]);
        REQUIRE(normalize_pose(view, wide.data(), other.data()) == Status::ok);
        float largest = 0.0f;
        for (std::size_t k = 0; k < D; ++k) largest = std::max(largest, std::fabs(other[k] - pose[k]));
        CHECK(largest > 0.01f);
    }
    // Every torso bone at one point: no size to measure.
    std::vector<float> collapsed(3 * J, 0.0f);
    for (std::size_t a = 0; a < 3; ++a) collapsed[a] = 1.0f;
    for (std::size_t j = 1; j < J; ++j)
        for (std::size_t a = 0; a < 3; ++a) collapsed[3 * j + a] = 1.0f;
    collapsed[3 * 1 + 2] += 1.0e-7f;  // hips a hair apart: a facing, no length
    CHECK(normalize_pose(view, collapsed.data(), pose.data()) == Status::degenerate_pose);
    // The lengths round-trip through the artifact; a model whose torso has no length is refused.
    const host::ModelData loaded = host::parse_model("torso.model", host::serialize_model(model));
    CHECK(loaded.bone_lengths == model.bone_lengths);
    CHECK(loaded.scale_mode == ScaleMode::torso);
    host::ModelData broken = host::parse_model("torso.model", host::serialize_model(model));
    for (float& length : broken.bone_lengths) length = 0.0f;
    const char* problem = nullptr;
    CHECK(validate_model(broken.view(), &problem) == Status::invalid_model);
    CHECK(std::string(problem) == "bone_lengths: no torso bone to scale by");
}

TEST_CASE("bone-length scaling: a bigger or differently built body gives the same pose") {
    const std::vector<host::LabelledClip> clips = host::toy_clips(host::make_toy_world(), 2, 4);
    const host::ModelData model = scaled_model(clips, ScaleMode::bone_lengths);
    const ModelView view = model.view();
    REQUIRE(uses_bones(view.scale_mode));
    REQUIRE(view.bone_lengths != nullptr);
    CHECK(view.bone_lengths[0] == 0.0f);  // the root has no bone
    CHECK(view.bone_lengths[3] > 0.1f);   // root → left hand

    const host::Clip& clip = clips.front().clip;
    const std::size_t J = clip.joint_count(), D = view.pose_dim();
    std::vector<float> skeleton(3 * J), pose(D), other(D);
    for (std::size_t f = 0; f < clip.frame_count(); f += 7) {
        const float* p = clip.frame(f);
        REQUIRE(normalize_pose(view, p, pose.data(), skeleton.data()) == Status::ok);
        // An adult 1.3× the size, and a child whose arms are half as long: every
        // bone keeps its direction, so the normalised pose is the same.
        for (const auto& [body, arms] : {std::pair<float, float>{1.3f, 1.3f}, {0.8f, 0.5f}}) {
            std::vector<float> q(p, p + 3 * J);
            for (std::size_t j = 1; j < J; ++j) {
                const float scale = j >= 3 ? arms : body;  // joints 3, 4 are the hands
                for (std::size_t a = 0; a < 3; ++a) q[3 * j + a] = p[a] + scale * (p[3 * j + a] - p[a]);
            }
            REQUIRE(normalize_pose(view, q.data(), other.data(), skeleton.data()) == Status::ok);
            for (std::size_t k = 0; k < D; ++k) CHECK(other[k] == doctest::Approx(pose[k]).epsilon(1e-5));
        }
    }
    // Without its scratch the bone-length model refuses rather than guess.
    CHECK(normalize_pose(view, clip.frame(0), pose.data()) == Status::invalid_argument);
    // The tree and lengths round-trip through the artifact, and a broken order is refused.
    const host::ModelData loaded = host::parse_model("bones.model", host::serialize_model(model));
    CHECK(loaded.bone_lengths == model.bone_lengths);
    host::ModelData broken = host::parse_model("bones.model", host::serialize_model(model));
    std::swap(broken.bone_order[0], broken.bone_order[1]);  // a child before the root
    const char* problem = nullptr;
    CHECK(validate_model(broken.view(), &problem) == Status::invalid_model);
    CHECK(std::string(problem).rfind("bone_order", 0) == 0);
}
