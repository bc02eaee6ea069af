// actionstring — stage 3: GMM posterior pose feature (design.md §1.3, paper §3).
//
// log N(z; μ_j, Σ_j) = log_normalizer_j − ½ ‖U_j (z − μ_j)‖², with the
// precision Σ_j⁻¹ = U_jᵀ U_j precomputed by the trainer, so the runtime never
// inverts a matrix or takes a determinant. Posteriors come from log-sum-exp.
#pragma once

#include <cmath>
#include <cstddef>

#include "actionstring/detail/lanes.hpp"
#include "actionstring/detail/math.hpp"
#include "actionstring/model.hpp"
#include "actionstring/status.hpp"

namespace actionstring {

/// Floats of scratch the GMM needs: one y = U (z − μ) per component of a block.
constexpr std::size_t gmm_scratch_floats(const ModelView& model) noexcept {
    return model.has_gmm() ? model.gmm_block_lanes(0) * model.feature_dim : 0u;
}

namespace detail {

#if defined(__GNUC__)
#define ACTIONSTRING_DETAIL_UNROLL _Pragma("GCC unroll 4")
#else
#define ACTIONSTRING_DETAIL_UNROLL
#endif

// L floats, one per component of a block, with the two operations the
// distances need. The loops over lanes are unrolled even at -Os, so on a
// Cortex-M4 (no SIMD) the pack lives in registers.
template <std::size_t L>
struct GmmPack {
    float v[L];
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack load(const float* p) noexcept {
        GmmPack a;
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = p[l];
        return a;
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE void store(float* p) const noexcept {
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) p[l] = v[l];
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack zero() noexcept {
        GmmPack a;
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = 0.0f;
        return a;
    }
    /// z_c − μ_j[c] for the block's components (means J × d, row by row).
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack centred(float z, const float* mean, std::size_t d) noexcept {
        GmmPack a;
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = z - mean[l * d];
        return a;
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator+(GmmPack a, GmmPack b) noexcept {
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = a.v[l] + b.v[l];
        return a;
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator*(GmmPack a, GmmPack b) noexcept {
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = a.v[l] * b.v[l];
        return a;
    }
};

#if ACTIONSTRING_DETAIL_LANES == 4
// Four components in SIMD lanes: each lane rounds the product, then the sum,
// exactly as the scalar pack does (no fused multiply-add), so the bits agree.
template <>
struct GmmPack<4> {
    Lanes x;
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack load(const float* p) noexcept { return {load_lanes(p)}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE void store(float* p) const noexcept { store_lanes(p, x); }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack zero() noexcept { return {detail::broadcast(0.0f)}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack centred(float z, const float* mean, std::size_t d) noexcept {
        return {detail::broadcast(z) - lanes_of(mean[0], mean[d], mean[2 * d], mean[3 * d])};
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator+(GmmPack a, GmmPack b) noexcept { return {a.x + b.x}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator*(GmmPack a, GmmPack b) noexcept { return {a.x * b.x}; }
};
#endif

// Squared Mahalanobis distances ‖U_j (z − μ_j)‖² of a feature to the L
// components first … first + L − 1 of one block (L = its lanes, 1 … 4).
//
// The block's factors are interleaved (ModelView::gmm_factor_index), so the
// loops walk them once, in memory order, with the L components side by side.
// Each component's arithmetic is the textbook order whatever L is: y[r] adds
// U[r][c] (z_c − μ_c) for c = r, r + 1, … (a product, then a sum, each rounded
// once: the runtime is built without fused multiply-adds), and q adds y[r]²
// for r = 0, 1, …. So a component's distance has the same bits in a block of
// four, in the last short block, in SIMD lanes or on a Cortex-M4.
// y: scratch of L · feature_dim floats, y[r · L + l]; q receives L floats.
template <std::size_t L>
inline void gmm_block_distances(const ModelView& model, std::size_t first, const float* feature, float* y,
                                float* q) noexcept {
    using Pack = GmmPack<L>;
    const std::size_t d = model.feature_dim;
    const float* u = model.gmm_factors + first * model.factor_size();
    const float* mean = model.gmm_means + first * d;
    Pack sum = Pack::zero();
    if (model.covariance == Covariance::diagonal) {
        for (std::size_t c = 0; c < d; ++c, u += L) {
            const Pack v = Pack::load(u) * Pack::centred(feature[c], mean + c, d);
            sum = sum + v * v;
        }
        sum.store(q);
        return;
    }
    for (std::size_t i = 0; i < L * d; ++i) y[i] = 0.0f;
    // U packed column by column (LAPACK 'U' packed): column c holds U[0..c][c].
    // Four columns go per pass over rows 0..c, so each y[r] is loaded and
    // stored once for four products (on a Cortex-M4 that halves the
    // instructions per product); rows c + 1..c + 3, which only the later
    // columns reach, are finished after it, each adding its terms in column order.
    std::size_t c = 0;
    for (; c + 4 <= d; c += 4) {
        const float* u0 = u;                 // column c:     rows 0..c
        const float* u1 = u0 + (c + 1) * L;  // column c + 1: rows 0..c + 1
        const float* u2 = u1 + (c + 2) * L;
        const float* u3 = u2 + (c + 3) * L;
        const Pack e0 = Pack::centred(feature[c], mean + c, d), e1 = Pack::centred(feature[c + 1], mean + c + 1, d);
        const Pack e2 = Pack::centred(feature[c + 2], mean + c + 2, d);
        const Pack e3 = Pack::centred(feature[c + 3], mean + c + 3, d);
        float* row = y;
        for (std::size_t r = 0; r <= c; ++r, row += L, u0 += L, u1 += L, u2 += L, u3 += L) {
            Pack s = Pack::load(row);
            s = s + Pack::load(u0) * e0;
            s = s + Pack::load(u1) * e1;
            s = s + Pack::load(u2) * e2;
            s = s + Pack::load(u3) * e3;
            s.store(row);
        }
        Pack s = Pack::load(row);  // row c + 1
        s = s + Pack::load(u1) * e1;
        s = s + Pack::load(u2) * e2;
        s = s + Pack::load(u3) * e3;
        s.store(row);
        row += L, u2 += L, u3 += L;
        s = Pack::load(row);  // row c + 2
        s = s + Pack::load(u2) * e2;
        s = s + Pack::load(u3) * e3;
        s.store(row);
        row += L, u3 += L;
        (Pack::load(row) + Pack::load(u3) * e3).store(row);  // row c + 3
        u = u3 + L;
    }
    for (; c < d; ++c) {
        const Pack e = Pack::centred(feature[c], mean + c, d);
        float* row = y;
        for (std::size_t r = 0; r <= c; ++r, row += L, u += L) (Pack::load(row) + Pack::load(u) * e).store(row);
    }
    for (std::size_t r = 0; r < d; ++r) {
        const Pack v = Pack::load(y + r * L);
        sum = sum + v * v;
    }
    sum.store(q);
}

#undef ACTIONSTRING_DETAIL_UNROLL

}  // namespace detail

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
            factor_sum += std::fabs(static_cast<double>(model.gmm_factors[model.gmm_factor_index(j, k)]));
        const double y_bound = factor_sum * diff_bound;  // bounds every |y_r|
        // q ≤ d·y², then ×0.5 and the finite log terms; keep a wide margin below FLT_MAX.
        if (!(static_cast<double>(d) * y_bound * y_bound < 1.0e36)) return false;
    }
    return true;
}

/// Writes log(w_j N(z; μ_j, Σ_j)) for every component.
/// @param feature    feature_dim floats; read only during the call
/// @param log_joint  receives component_count floats (caller-owned)
/// @param scratch    gmm_scratch_floats(model) floats (caller-owned)
inline Status gmm_log_joint(const ModelView& model, const float* feature, float* log_joint, float* scratch) noexcept {
    if (feature == nullptr || log_joint == nullptr || scratch == nullptr) return Status::invalid_argument;
    const std::size_t J = model.component_count;
    for (std::size_t first = 0; first < J; first += ModelView::gmm_block) {
        float q[ModelView::gmm_block];
        const std::size_t lanes = model.gmm_block_lanes(first);
        switch (lanes) {
            case 4: detail::gmm_block_distances<4>(model, first, feature, scratch, q); break;
            case 3: detail::gmm_block_distances<3>(model, first, feature, scratch, q); break;
            case 2: detail::gmm_block_distances<2>(model, first, feature, scratch, q); break;
            default: detail::gmm_block_distances<1>(model, first, feature, scratch, q); break;
        }
        for (std::size_t l = 0; l < lanes; ++l) {
            const std::size_t j = first + l;
            log_joint[j] = model.gmm_log_weights[j] + model.gmm_log_normalizers[j] - 0.5f * q[l];
        }
    }
    return Status::ok;
}

/// The pose feature t = [p(1|z) … p(J|z)] (paper eq. 5).
///
/// Always sums to 1 and is never all zero: far from every key-pose the nearest
/// component (in likelihood) takes the mass instead of every term underflowing.
///
/// @param feature         feature_dim floats; read only during the call
/// @param posterior       receives component_count floats (caller-owned)
/// @param scratch         gmm_scratch_floats(model) floats (caller-owned)
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
