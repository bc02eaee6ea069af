// actionstring — stage 3: GMM posterior pose feature (design.md §1.3, paper §3).
//
// log N(z; μ_j, Σ_j) = log_normalizer_j − ½ ‖U_j (z − μ_j)‖², with the
// precision Σ_j⁻¹ = U_jᵀ U_j precomputed by the trainer, so the runtime never
// inverts a matrix or takes a determinant. Posteriors come from log-sum-exp.
#pragma once

#include <cmath>
#include <cstddef>

#include "actionstring/detail/axpy.hpp"
#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"

namespace actionstring {

/// Squared Mahalanobis distance ‖U_j (z − μ_j)‖² of a feature to component j.
/// @param scratch feature_dim floats (caller-owned; the full covariance's y = U (z − μ))
inline float gmm_mahalanobis_sq(const ModelView& model, std::size_t component, const float* feature,
                                float* scratch) noexcept {
    const std::size_t d = model.feature_dim;
    const float* mean = model.gmm_means + component * d;
    const float* factor = model.gmm_factors + component * model.factor_size();
    float q = 0.0f;
    if (model.covariance == Covariance::diagonal) {
        for (std::size_t c = 0; c < d; ++c) {
            const float y = factor[c] * (feature[c] - mean[c]);
            q += y * y;
        }
        return q;
    }
    // U packed column by column (LAPACK 'U' packed): column c holds U[0..c][c].
    // Accumulating y[r] column by column keeps every sum in one fixed order
    // (increasing c) while the inner loop over r is independent, so it
    // vectorises. Four columns go per pass over rows 0..c (detail/axpy.hpp);
    // rows c + 1..c + 3, which only the later of the four columns reach, are
    // finished after it, each adding its terms in the same column order.
    float* y = scratch;
    for (std::size_t r = 0; r < d; ++r) y[r] = 0.0f;
    std::size_t c = 0;
    for (; c + 4 <= d; c += 4) {
        const float* u0 = factor;          // column c:     rows 0..c
        const float* u1 = u0 + (c + 1);    // column c + 1: rows 0..c + 1
        const float* u2 = u1 + (c + 2);
        const float* u3 = u2 + (c + 3);
        const float e0 = feature[c] - mean[c], e1 = feature[c + 1] - mean[c + 1];
        const float e2 = feature[c + 2] - mean[c + 2], e3 = feature[c + 3] - mean[c + 3];
        detail::axpy4(y, c + 1, u0, e0, u1, e1, u2, e2, u3, e3);
        float sum = y[c + 1];
        sum += u1[c + 1] * e1;
        sum += u2[c + 1] * e2;
        sum += u3[c + 1] * e3;
        y[c + 1] = sum;
        sum = y[c + 2];
        sum += u2[c + 2] * e2;
        sum += u3[c + 2] * e3;
        y[c + 2] = sum;
        y[c + 3] += u3[c + 3] * e3;
        factor = u3 + (c + 4);
    }
    for (; c < d; ++c) {
        detail::axpy1(y, c + 1, factor, feature[c] - mean[c]);
        factor += c + 1;
    }
    for (std::size_t r = 0; r < d; ++r) q += y[r] * y[r];
    return q;
}

/// True when no pose within max_pose_coordinate of the root can drive a
/// component's squared distance past float range, so gmm_posterior() cannot
/// fail on a pose that normalize_pose() accepted. Bounds every term in double.
inline bool gmm_is_overflow_safe(const ModelView& model, float max_coordinate) noexcept {
    const std::size_t pose_dim = model.input_dim();  // velocities are bounded like coordinates
    const std::size_t d = model.feature_dim;
    const double coordinate_bound = static_cast<double>(max_coordinate);
    double feature_bound = coordinate_bound;
    if (model.has_projection()) {
        double mean_bound = 0.0;
        for (std::size_t c = 0; c < pose_dim; ++c) {
            const double v = std::fabs(static_cast<double>(model.projection_mean[c]));
            if (v > mean_bound) mean_bound = v;
        }
        feature_bound = 0.0;
        for (std::size_t r = 0; r < d; ++r) {
            double row = 0.0;
            for (std::size_t c = 0; c < pose_dim; ++c)
                row += std::fabs(static_cast<double>(model.projection_matrix[c * d + r]));
            row *= coordinate_bound + mean_bound;
            if (row > feature_bound) feature_bound = row;
        }
    }
    for (std::size_t j = 0; j < model.component_count; ++j) {
        double diff_bound = 0.0;
        for (std::size_t c = 0; c < d; ++c) {
            const double v = feature_bound + std::fabs(static_cast<double>(model.gmm_means[j * d + c]));
            if (v > diff_bound) diff_bound = v;
        }
        double factor_sum = 0.0;
        const std::size_t size = model.factor_size();
        for (std::size_t k = 0; k < size; ++k)
            factor_sum += std::fabs(static_cast<double>(model.gmm_factors[j * size + k]));
        const double y_bound = factor_sum * diff_bound;  // bounds every |y_r|
        // q ≤ d·y², then ×0.5 and the finite log terms; keep a wide margin below FLT_MAX.
        if (!(static_cast<double>(d) * y_bound * y_bound < 1.0e36)) return false;
    }
    return true;
}

/// Writes log(w_j N(z; μ_j, Σ_j)) for every component.
/// @param feature    feature_dim floats; read only during the call
/// @param log_joint  receives component_count floats (caller-owned)
/// @param scratch    feature_dim floats (caller-owned)
inline Status gmm_log_joint(const ModelView& model, const float* feature, float* log_joint, float* scratch) noexcept {
    if (feature == nullptr || log_joint == nullptr || scratch == nullptr) return Status::invalid_argument;
    for (std::size_t j = 0; j < model.component_count; ++j)
        log_joint[j] = model.gmm_log_weights[j] + model.gmm_log_normalizers[j] -
                       0.5f * gmm_mahalanobis_sq(model, j, feature, scratch);
    return Status::ok;
}

/// The pose feature t = [p(1|z) … p(J|z)] (paper eq. 5).
///
/// Always sums to 1 and is never all zero: far from every key-pose the nearest
/// component (in likelihood) takes the mass instead of every term underflowing.
///
/// @param feature         feature_dim floats; read only during the call
/// @param posterior       receives component_count floats (caller-owned)
/// @param scratch         feature_dim floats (caller-owned)
/// @param log_likelihood  if not null, receives log p(z) under the mixture
/// @return ok, invalid_argument (a null pointer), or pose_out_of_range when
///         no likelihood is finite in float
inline Status gmm_posterior(const ModelView& model, const float* feature, float* posterior, float* scratch,
                            float* log_likelihood = nullptr) noexcept {
    const Status status = gmm_log_joint(model, feature, posterior, scratch);
    if (status != Status::ok) return status;
    const std::size_t J = model.component_count;
    float peak = -detail::infinity();
    for (std::size_t j = 0; j < J; ++j) {
        if (detail::is_nan(posterior[j])) return Status::pose_out_of_range;
        if (posterior[j] > peak) peak = posterior[j];
    }
    if (!detail::is_finite(peak)) return Status::pose_out_of_range;
    float sum = 0.0f;
    for (std::size_t j = 0; j < J; ++j) {
        posterior[j] = detail::exp_portable(posterior[j] - peak);
        sum += posterior[j];
    }
    // sum ≥ 1: the peak term is exp(0).
    const float inverse = 1.0f / sum;
    for (std::size_t j = 0; j < J; ++j) posterior[j] *= inverse;
    if (log_likelihood != nullptr) *log_likelihood = peak + detail::log_portable(sum);
    return Status::ok;
}

}  // namespace actionstring
