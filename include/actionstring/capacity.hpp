// actionstring — compile-time capacities of the state objects.
//
// Every state object sizes its storage from a Capacity at compile time, built
// from a limits type whose members name each bound. A generated model header
// emits one that fits its model exactly; host tools use a generous one and
// load any model that fits.
#pragma once

#include <cstddef>

#include "actionstring/model.hpp"

namespace actionstring {

/// Defaults for the optional members of a limits type. Derive a limits type
/// from it and name every size the state objects need, each a
/// `static constexpr` member:
///
///     struct MyLimits : actionstring::DefaultLimits {
///         static constexpr std::size_t joints = 31;        // joints per input frame
///         static constexpr std::size_t pose_joints = 30;   // joints in the pose vector (D = 3 × this)
///         static constexpr std::size_t feature_dim = 24;   // d after projection (≤ 3 × pose_joints)
///         static constexpr std::size_t components = 20;    // J, GMM components (1 for a model without a GMM)
///         static constexpr std::size_t representatives = 22;        // R, representative strings
///         static constexpr std::size_t representative_chars = 701;  // characters over all representatives
///     };
///     using MyCapacity = actionstring::Capacity<MyLimits>;
///
/// A generated model header emits such a type (ModelLimits) that fits its model exactly.
struct DefaultLimits {
    /// Sliding windows open at once (≥ ceil(window / step)); 0 leaves the
    /// paper's window rule out of the Annotator, and its state with it.
    static constexpr std::size_t windows = 0;
    /// Whether the state can track warping-path lengths (needed only for
    /// LengthNormalization::path).
    static constexpr bool path_lengths = true;
    /// Longest settle delay of the segmenter, in characters.
    static constexpr std::size_t settle_chars = 48;
    /// Whether the state can hold models with motion (velocity) input: a ring
    /// of recent poses and inputs twice the pose's length.
    static constexpr bool motion = false;
};

/// Upper bounds on model sizes, fixed at compile time, read from the named
/// members of `Limits` (see DefaultLimits). Every state object sizes its
/// storage from one.
template <class Limits>
struct Capacity {
    static_assert(Limits::joints > 0 && Limits::pose_joints > 0 && Limits::feature_dim > 0 && Limits::components > 0 &&
                      Limits::representatives > 0 && Limits::representative_chars > 0,
                  "every capacity must be positive");
    // Reads every member at instantiation, so none of a limits type goes unused.
    static_assert(Limits::windows < (std::size_t{1} << 16) && Limits::settle_chars > 0 &&
                      (Limits::path_lengths || !Limits::path_lengths) && (Limits::motion || !Limits::motion),
                  "windows below 65536 and settle_chars above 0");
    using limits = Limits;
    static constexpr std::size_t max_joints = Limits::joints;
    static constexpr std::size_t max_pose_dim = 3 * Limits::pose_joints;
    static constexpr std::size_t max_feature_dim = Limits::feature_dim;
    static constexpr std::size_t max_components = Limits::components;
    static constexpr std::size_t max_representatives = Limits::representatives;
    static constexpr std::size_t max_representative_chars = Limits::representative_chars;
    static constexpr std::size_t max_windows = Limits::windows;
    static constexpr bool path_lengths = Limits::path_lengths;
    static constexpr std::size_t max_settle_chars = Limits::settle_chars;
    static constexpr bool has_motion = Limits::motion;
    /// Poses the velocity ring keeps (motion.hpp); one, unused, without motion.
    static constexpr std::size_t motion_ring = has_motion ? 6 : 1;
    /// What the projection reads: the pose, and with motion its velocity.
    static constexpr std::size_t max_input_dim = has_motion ? 2 * max_pose_dim : max_pose_dim;
    /// Whether the Annotator runs the paper's sliding-window rule.
    static constexpr bool has_windows = max_windows > 0;
    /// The same bounds without the window rule: the segmenter alone labels the
    /// stream, and the window matcher's state (the largest part) is not paid for.
    struct LimitsWithoutWindows : Limits {
        static constexpr std::size_t windows = 0;
    };
    using without_windows = Capacity<LimitsWithoutWindows>;
    /// DP cells one window keeps: one row or column of length(rep) + 1 per representative.
    static constexpr std::size_t cells_per_window = max_representative_chars + max_representatives;

    /// True when the feature tables fit (what a StringEncoder needs).
    static constexpr bool fits_features(const ModelView& m) noexcept {
        return m.joint_count <= max_joints && m.pose_dim() <= max_pose_dim && m.input_dim() <= max_input_dim &&
               (has_motion || !m.has_motion()) && m.feature_dim <= max_feature_dim &&
               m.component_count <= max_components;
    }

    /// True when the matching tables fit (what a WindowMatcher needs).
    static constexpr bool fits_matching(const ModelView& m) noexcept {
        return m.representative_count <= max_representatives &&
               m.total_representative_chars() <= max_representative_chars &&
               (max_windows == 0 || m.max_open_windows() <= max_windows) &&
               (path_lengths || m.normalization != LengthNormalization::path);
    }

    /// True when the whole model fits these bounds (the model itself is checked by validate_model).
    static constexpr bool fits(const ModelView& m) noexcept { return fits_features(m) && fits_matching(m); }
};

/// Bounds for host tools: Kinect v2 and ASF skeletons, J ≤ 64, up to 512
/// representatives of 64 characters on average, windows up to 8 steps long,
/// settle delays up to 1024 characters (60 s at 12 Hz, the CLI's limit).
struct HostLimits : DefaultLimits {
    static constexpr std::size_t joints = 32;
    static constexpr std::size_t pose_joints = 32;
    static constexpr std::size_t feature_dim = 96;
    static constexpr std::size_t components = 64;
    static constexpr std::size_t representatives = 512;
    static constexpr std::size_t representative_chars = 32768;
    static constexpr std::size_t windows = 8;
    static constexpr std::size_t settle_chars = 1024;
    static constexpr bool motion = true;
};
using HostCapacity = Capacity<HostLimits>;

}  // namespace actionstring
