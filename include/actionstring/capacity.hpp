// actionstring — compile-time capacities of the state objects.
//
// Every state object sizes its storage from a Capacity at compile time. A
// generated model header emits a Capacity that fits its model exactly; host
// tools use a generous one and load any model that fits.
#pragma once

#include <cstddef>

#include "actionstring/model.hpp"

namespace actionstring {

/// Upper bounds on model sizes, fixed at compile time.
/// @tparam Joints              joints per input frame
/// @tparam PoseJoints          joints in the pose vector (D = 3 × PoseJoints)
/// @tparam FeatureDim          d after projection (≤ 3 × PoseJoints)
/// @tparam Components          J, GMM components
/// @tparam Representatives     R, representative strings
/// @tparam RepresentativeChars total characters over all representatives
/// @tparam Windows             sliding windows open at once (≥ ceil(window / step));
///                             0 leaves the paper's window rule out of the Annotator
/// @tparam PathLengths         whether the state can track warping-path lengths
///                             (needed only for LengthNormalization::path)
/// @tparam SettleChars         longest settle delay of the segmenter, in characters
template <std::size_t Joints, std::size_t PoseJoints, std::size_t FeatureDim,
          std::size_t Components, std::size_t Representatives,
          std::size_t RepresentativeChars, std::size_t Windows, bool PathLengths = true,
          std::size_t SettleChars = 48>
struct Capacity {
    static_assert(Joints > 0 && PoseJoints > 0 && FeatureDim > 0 && Components > 0 &&
                      Representatives > 0 && RepresentativeChars > 0,
                  "every capacity must be positive");
    static constexpr std::size_t max_joints = Joints;
    static constexpr std::size_t max_pose_dim = 3 * PoseJoints;
    static constexpr std::size_t max_feature_dim = FeatureDim;
    static constexpr std::size_t max_components = Components;
    static constexpr std::size_t max_representatives = Representatives;
    static constexpr std::size_t max_representative_chars = RepresentativeChars;
    static constexpr std::size_t max_windows = Windows;
    static constexpr bool path_lengths = PathLengths;
    static constexpr std::size_t max_settle_chars = SettleChars;
    /// Whether the Annotator runs the paper's sliding-window rule.
    static constexpr bool has_windows = Windows > 0;
    /// The same bounds without the window rule: the segmenter alone labels the
    /// stream, and the window matcher's state (the largest part) is not paid for.
    using without_windows = Capacity<Joints, PoseJoints, FeatureDim, Components, Representatives,
                                     RepresentativeChars, 0, PathLengths, SettleChars>;
    /// DP cells one window keeps: one row or column of length(rep) + 1 per representative.
    static constexpr std::size_t cells_per_window = RepresentativeChars + Representatives;

    /// True when the feature tables fit (what a StringEncoder needs).
    static constexpr bool fits_features(const ModelView& m) noexcept {
        return m.joint_count <= max_joints && m.pose_dim() <= max_pose_dim &&
               m.feature_dim <= max_feature_dim && m.component_count <= max_components;
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
/// representatives of 64 characters on average, windows up to 8 steps long.
using HostCapacity = Capacity<32, 32, 96, 64, 512, 32768, 8>;

}  // namespace actionstring
