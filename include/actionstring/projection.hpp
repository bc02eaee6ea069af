// actionstring — stage 2: optional linear projection z = P (x − m) (design.md §1.2).
#pragma once

#include <cstddef>

#include "actionstring/detail/axpy.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"

namespace actionstring {

/// Part of project_pose(), for a caller that spreads it over several calls
/// (AnnotatorConfig::spread_work): adds the pose's coordinates [first, last)
/// to the feature, clearing it first when first is 0. first and last are
/// multiples of four, or last is input_dim(); taking 0 … input_dim() in any
/// such steps gives project_pose()'s bits.
inline void project_pose_columns(const ModelView& model, const float* pose, float* feature, std::size_t first,
                                 std::size_t last) noexcept {
    if (!model.has_projection()) {
        for (std::size_t i = first; i < last; ++i) feature[i] = pose[i];
        return;
    }
    // Column by column: the d outputs are independent accumulators, each summed
    // in one fixed order (increasing c), four columns per pass (detail/axpy.hpp).
    const std::size_t d = model.feature_dim;
    const float* mean = model.projection_mean;
    if (first == 0)
        for (std::size_t r = 0; r < d; ++r) feature[r] = 0.0f;
    const float* column = model.projection_matrix + first * d;
    std::size_t c = first;
    for (; c + 4 <= last; c += 4, column += 4 * d)
        detail::axpy4(feature, d, column, pose[c] - mean[c], column + d, pose[c + 1] - mean[c + 1], column + 2 * d,
                      pose[c + 2] - mean[c + 2], column + 3 * d, pose[c + 3] - mean[c + 3]);
    for (; c < last; ++c, column += d) detail::axpy1(feature, d, column, pose[c] - mean[c]);
}

/// Projects a normalised pose onto the model's feature space. Without a
/// projection in the model the pose is copied unchanged.
///
/// Sums run in a fixed order over plain loops on purpose: a vectorised kernel
/// that peels by pointer alignment would make a generated-table build and a
/// host-loaded artifact differ in the last bit.
///
/// @param pose     input_dim() floats: the pose from normalize_pose(), then with
///                 motion its velocity (motion.hpp); read only during the call
/// @param feature  receives feature_dim floats (caller-owned); may not alias pose
inline Status project_pose(const ModelView& model, const float* pose, float* feature) noexcept {
    if (pose == nullptr || feature == nullptr) return Status::invalid_argument;
    project_pose_columns(model, pose, feature, 0, model.input_dim());
    return Status::ok;
}

}  // namespace actionstring
