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

/// Floats of scratch the GMM needs: one z − μ per component of a block (of
/// two blocks with AVX2, which computes two at once: the size depends on how
/// the runtime was compiled, so size state with this function, never a number).
constexpr std::size_t gmm_scratch_floats(const ModelView& model) noexcept {
#if ACTIONSTRING_DETAIL_WIDE_LANES == 8
    if (model.has_gmm() && model.component_count > ModelView::gmm_block)
        return 2 * ModelView::gmm_block * model.feature_dim;
#endif
    return model.has_gmm() ? model.gmm_block_lanes(0) * model.feature_dim : 0u;
}

namespace detail {

#if defined(__GNUC__)
#define ACTIONSTRING_DETAIL_UNROLL _Pragma("GCC unroll 4")
#define ACTIONSTRING_DETAIL_UNROLL_ROWS _Pragma("GCC unroll 8")
#else
#define ACTIONSTRING_DETAIL_UNROLL
#define ACTIONSTRING_DETAIL_UNROLL_ROWS
#endif

// L floats, one per component of a block, with the operations the distances
// need. The loops over lanes are unrolled even at -Os, so on a Cortex-M4 (no
// SIMD) the pack lives in registers.
template <std::size_t L>
struct GmmPack {
    float v[L];
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack load(const float* p) noexcept {
        GmmPack a;
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = p[l];
        return a;
    }
    /// A factor element of the block's components (`half` serves packs of two blocks).
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack load_factor(const float* p, std::size_t /*half*/) noexcept {
        return load(p);
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE void store(float* p) const noexcept {
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) p[l] = v[l];
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack zero() noexcept { return broadcast(0.0f); }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack broadcast(float x) noexcept {
        GmmPack a;
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = x;
        return a;
    }
    /// z_c − μ_j[c] for the block's components (means J × d, row by row).
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack centred(float z, const float* mean, std::size_t d) noexcept {
        GmmPack a;
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = z - mean[l * d];
        return a;
    }
    /// centred() for c = 0 … d − 1, stored at e + c · L.
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static void centre_all(const float* z, const float* mean, std::size_t d,
                                                             float* e) noexcept {
        for (std::size_t c = 0; c < d; ++c) centred(z[c], mean + c, d).store(e + c * L);
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator+(GmmPack a, GmmPack b) noexcept {
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = a.v[l] + b.v[l];
        return a;
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator-(GmmPack a, GmmPack b) noexcept {
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = a.v[l] - b.v[l];
        return a;
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator*(GmmPack a, GmmPack b) noexcept {
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) a.v[l] = a.v[l] * b.v[l];
        return a;
    }
    /// a < b in every lane (false when any lane is NaN).
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend bool all_less(GmmPack a, GmmPack b) noexcept {
        bool all = true;
        ACTIONSTRING_DETAIL_UNROLL for (std::size_t l = 0; l < L; ++l) all = all && a.v[l] < b.v[l];
        return all;
    }
};

#if ACTIONSTRING_DETAIL_LANES == 4
// Four components in SIMD lanes: each lane rounds the product, then the sum,
// exactly as the scalar pack does (no fused multiply-add), so the bits agree.
template <>
struct GmmPack<4> {
    Lanes x;
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack load(const float* p) noexcept { return {load_lanes(p)}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack load_factor(const float* p, std::size_t /*half*/) noexcept {
        return {load_lanes(p)};
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE void store(float* p) const noexcept { store_lanes(p, x); }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack zero() noexcept { return {detail::broadcast(0.0f)}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack broadcast(float v) noexcept { return {detail::broadcast(v)}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack centred(float z, const float* mean, std::size_t d) noexcept {
        return {detail::broadcast(z) - lanes_of(mean[0], mean[d], mean[2 * d], mean[3 * d])};
    }
    // Four coordinates of each component at once (the means are rows), then a
    // 4 × 4 transpose into the lanes: the same subtractions, fewer shuffles
    // than gathering each coordinate's four means. Coordinate c's four values
    // go to e + c · stride (stride 4 here; 8 for the first or second half of
    // GmmPack<8>).
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static void centre_strided(const float* z, const float* mean, std::size_t d,
                                                                 float* e, std::size_t stride) noexcept {
        std::size_t c = 0;
        for (; c + 4 <= d; c += 4) {
            const __m128 zc = _mm_loadu_ps(z + c);
            __m128 r0 = _mm_sub_ps(zc, _mm_loadu_ps(mean + c)), r1 = _mm_sub_ps(zc, _mm_loadu_ps(mean + d + c));
            __m128 r2 = _mm_sub_ps(zc, _mm_loadu_ps(mean + 2 * d + c));
            __m128 r3 = _mm_sub_ps(zc, _mm_loadu_ps(mean + 3 * d + c));
            _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
            _mm_storeu_ps(e + stride * c, r0);
            _mm_storeu_ps(e + stride * (c + 1), r1);
            _mm_storeu_ps(e + stride * (c + 2), r2);
            _mm_storeu_ps(e + stride * (c + 3), r3);
        }
        for (; c < d; ++c) centred(z[c], mean + c, d).store(e + stride * c);
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static void centre_all(const float* z, const float* mean, std::size_t d,
                                                             float* e) noexcept {
        centre_strided(z, mean, d, e, 4);
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator+(GmmPack a, GmmPack b) noexcept { return {a.x + b.x}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator-(GmmPack a, GmmPack b) noexcept { return {a.x - b.x}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator*(GmmPack a, GmmPack b) noexcept { return {a.x * b.x}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend bool all_less(GmmPack a, GmmPack b) noexcept {
        return detail::all_less(a.x, b.x);
    }
};
#endif

#if ACTIONSTRING_DETAIL_WIDE_LANES == 8
// Two whole blocks side by side (AVX2): lanes 0–3 are the first block's
// components, lanes 4–7 the next block's. The model keeps its blocks of four;
// a factor element loads as two halves, the second `half` floats further on.
template <>
struct GmmPack<8> {
    Lanes8 x;
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack load(const float* p) noexcept { return {load_lanes8(p)}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack load_factor(const float* p, std::size_t half) noexcept {
        return {Lanes8{_mm256_loadu2_m128(p + half, p)}};
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE void store(float* p) const noexcept { store_lanes(p, x); }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack zero() noexcept { return {broadcast8(0.0f)}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static GmmPack broadcast(float v) noexcept { return {broadcast8(v)}; }
    // Each block's z − μ as GmmPack<4> computes it, eight floats per coordinate.
    ACTIONSTRING_DETAIL_ALWAYS_INLINE static void centre_all(const float* z, const float* mean, std::size_t d,
                                                             float* e) noexcept {
        GmmPack<4>::centre_strided(z, mean, d, e, 8);
        GmmPack<4>::centre_strided(z, mean + ModelView::gmm_block * d, d, e + 4, 8);
    }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator+(GmmPack a, GmmPack b) noexcept { return {a.x + b.x}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator-(GmmPack a, GmmPack b) noexcept { return {a.x - b.x}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend GmmPack operator*(GmmPack a, GmmPack b) noexcept { return {a.x * b.x}; }
    ACTIONSTRING_DETAIL_ALWAYS_INLINE friend bool all_less(GmmPack a, GmmPack b) noexcept {
        return detail::all_less(a.x, b.x);
    }
};
#endif

// Rows r … r + G − 1 of y = U (z − μ) for the L components of a block, each
// in the textbook order (c = r, r + 1, … d − 1), their squares added to `sum`
// in row order. U is packed column by column: U[r][c] is element
// c(c + 1)/2 + r, so the group's rows of one column are adjacent and one pass
// over the columns serves all G rows (G independent chains of additions).
// With eight lanes (two blocks) the factors keep their blocks' layout of four
// lanes per element, and the second block's lie `half` floats after the first's.
template <std::size_t L, std::size_t G>
ACTIONSTRING_DETAIL_ALWAYS_INLINE inline GmmPack<L> gmm_rows(const float* u, std::size_t half, const float* e,
                                                            std::size_t r, std::size_t d, GmmPack<L> sum) noexcept {
    using Pack = GmmPack<L>;
    constexpr std::size_t S = L > ModelView::gmm_block ? ModelView::gmm_block : L;  // floats per factor element
    Pack y[G];
    ACTIONSTRING_DETAIL_UNROLL_ROWS for (std::size_t i = 0; i < G; ++i) y[i] = Pack::zero();
    const float* column = u + (r * (r + 1) / 2 + r) * S;  // column r, row r
    // The triangle: column r + t reaches rows r … r + t only.
    ACTIONSTRING_DETAIL_UNROLL_ROWS for (std::size_t t = 0; t + 1 < G; ++t) {
        const Pack ec = Pack::load(e + (r + t) * L);
        ACTIONSTRING_DETAIL_UNROLL_ROWS for (std::size_t i = 0; i <= t; ++i) y[i] =
            y[i] + Pack::load_factor(column + i * S, half) * ec;
        column += (r + t + 1) * S;
    }
    for (std::size_t c = r + G - 1; c < d; ++c) {
        const Pack ec = Pack::load(e + c * L);
        ACTIONSTRING_DETAIL_UNROLL_ROWS for (std::size_t i = 0; i < G; ++i) y[i] =
            y[i] + Pack::load_factor(column + i * S, half) * ec;
        column += (c + 1) * S;
    }
    ACTIONSTRING_DETAIL_UNROLL_ROWS for (std::size_t i = 0; i < G; ++i) sum = sum + y[i] * y[i];
    return sum;
}

// Rows per group, where a block may stop: with SIMD a first group of four,
// then eight (eight chains keep the adder busy, and on HDM05 at J = 40 most
// blocks that stop do so within twelve rows); four on a Cortex-M4, whose 32
// float registers hold four rows of four lanes.
#if ACTIONSTRING_DETAIL_LANES == 4
constexpr std::size_t gmm_group_rows = 8;
#else
constexpr std::size_t gmm_group_rows = 4;
#endif

// Squared Mahalanobis distances ‖U_j (z − μ_j)‖² of a feature to the L
// components first … first + L − 1 of one block (L = its lanes, 1 … 4), or of
// two whole blocks side by side (L = 8, with AVX2 and full covariance).
//
// Each component's arithmetic is the textbook order whatever L is: y[r] adds
// U[r][c] (z_c − μ_c) for c = r, r + 1, … (a product, then a sum, each rounded
// once: the runtime is built without fused multiply-adds), and q adds y[r]²
// for r = 0, 1, …. So a component's distance has the same bits in a block of
// four, in the last short block, in SIMD lanes or on a Cortex-M4.
//
// The rows are computed a group at a time, in order, and q grows only by
// squares, so after each group q is a lower bound of the distance and
// log w_j + log normalizer_j − ½ q an upper bound of the log joint (rounding is
// monotone, so the bound holds in float too). When `peak` is given (the
// largest log joint found so far) and every component's bound lies more than
// exp's underflow below it, their posteriors are 0 whatever the remaining
// rows add: the block stops there and returns false (q is then not written).
// Most components of a large mixture are that far from a pose.
// e: scratch of L · feature_dim floats; q receives L floats.
template <std::size_t L>
inline bool gmm_block_distances(const ModelView& model, std::size_t first, const float* feature, float* e, float* q,
                                const float* peak) noexcept {
    using Pack = GmmPack<L>;
    const std::size_t d = model.feature_dim;
    const float* u = model.gmm_factors + first * model.factor_size();
    const float* mean = model.gmm_means + first * d;
    // The upper bounds of the log joints, in gmm_log_joint_of()'s own expression.
    Pack constants = Pack::zero(), peaks = Pack::zero();
    const Pack half = Pack::broadcast(0.5f), limit = Pack::broadcast(exp_underflow_bound);
    if (peak != nullptr) {
        float c[L];
        for (std::size_t l = 0; l < L; ++l) c[l] = model.gmm_log_weights[first + l] + model.gmm_log_normalizers[first + l];
        constants = Pack::load(c);
        peaks = Pack::broadcast(*peak);
    }
    auto negligible = [&](Pack sum) ACTIONSTRING_DETAIL_ALWAYS_INLINE {
        return peak != nullptr && all_less((constants - half * sum) - peaks, limit);
    };
    Pack sum = Pack::zero();
    if constexpr (L <= ModelView::gmm_block) {  // pairs of blocks are for full covariance only
        if (model.covariance == Covariance::diagonal) {
            for (std::size_t c = 0; c < d; ++c, u += L) {
                const Pack v = Pack::load(u) * Pack::centred(feature[c], mean + c, d);
                sum = sum + v * v;
                if (c % gmm_group_rows == gmm_group_rows - 1 && negligible(sum)) return false;
            }
            sum.store(q);
            return true;
        }
    }
    const std::size_t second = ModelView::gmm_block * model.factor_size();  // the next block's factors
    Pack::centre_all(feature, mean, d, e);
    std::size_t r = 0;
    if (gmm_group_rows > 4 && d > 8) {  // a first check after four rows
        sum = gmm_rows<L, 4>(u, second, e, r, d, sum);
        r = 4;
        if (negligible(sum)) return false;
    }
    for (; r + gmm_group_rows <= d; r += gmm_group_rows) {
        sum = gmm_rows<L, gmm_group_rows>(u, second, e, r, d, sum);
        if (r + gmm_group_rows < d && negligible(sum)) return false;
    }
    if (gmm_group_rows > 4 && r + 4 <= d) {
        sum = gmm_rows<L, 4>(u, second, e, r, d, sum);
        r += 4;
    }
    for (; r < d; ++r) sum = gmm_rows<L, 1>(u, second, e, r, d, sum);
    sum.store(q);
    return true;
}

// The distances of the block starting at `first` (a multiple of gmm_block).
inline bool gmm_distances(const ModelView& model, std::size_t first, const float* feature, float* scratch, float* q,
                          const float* peak) noexcept {
    switch (model.gmm_block_lanes(first)) {
        case 4: return gmm_block_distances<4>(model, first, feature, scratch, q, peak);
        case 3: return gmm_block_distances<3>(model, first, feature, scratch, q, peak);
        case 2: return gmm_block_distances<2>(model, first, feature, scratch, q, peak);
        default: return gmm_block_distances<1>(model, first, feature, scratch, q, peak);
    }
}

// log(w_j N(z; μ_j, Σ_j)) from the squared distance, in one expression for every caller.
inline float gmm_log_joint_of(const ModelView& model, std::size_t j, float q) noexcept {
    return model.gmm_log_weights[j] + model.gmm_log_normalizers[j] - 0.5f * q;
}

#undef ACTIONSTRING_DETAIL_UNROLL
#undef ACTIONSTRING_DETAIL_UNROLL_ROWS

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
        detail::gmm_distances(model, first, feature, scratch, q, nullptr);
        for (std::size_t l = 0; l < model.gmm_block_lanes(first); ++l)
            log_joint[first + l] = detail::gmm_log_joint_of(model, first + l, q[l]);
    }
    return Status::ok;
}

/// A posterior in the making, a few blocks of components at a time
/// (gmm_pass_begin(), gmm_pass_advance(), gmm_pass_finish()): so a caller that
/// spreads a frame's work (AnnotatorConfig::spread_work) can stop between
/// blocks. gmm_posterior() is the same three calls in one go; the blocks come
/// in the same order whatever the steps, so the result has the same bits.
struct GmmPass {
    std::size_t start = 0;  ///< The block computed first (the last peak's).
    std::size_t done = 0;   ///< Components (of whole blocks) taken so far.
    std::size_t first = 0;  ///< The next block's first component.
    float peak = 0.0f;      ///< The largest log joint so far.
    std::size_t best = 0;   ///< Its component (the first of equals).
    bool failed = false;    ///< A log joint was NaN (pose_out_of_range).
};

/// Starts a pass; `most_probable` as gmm_posterior()'s on entry.
inline void gmm_pass_begin(const ModelView& model, GmmPass& pass, std::size_t most_probable) noexcept {
    const std::size_t block = ModelView::gmm_block;
    pass = GmmPass{};
    pass.start = most_probable < model.component_count ? most_probable - most_probable % block : 0;
    pass.first = pass.start;
    pass.peak = -detail::infinity();
}

/// Blocks of components a pass has left.
inline std::size_t gmm_pass_blocks_left(const ModelView& model, const GmmPass& pass) noexcept {
    const std::size_t block = ModelView::gmm_block;
    return pass.failed ? 0u : (model.component_count - pass.done + block - 1) / block;
}

/// Takes up to `blocks` more blocks' log joints into `posterior` (at least one;
/// two at once with AVX2 may take one more). Returns whether blocks are left.
/// Arguments as gmm_posterior()'s; `feature` must hold the same values all pass.
inline bool gmm_pass_advance(const ModelView& model, GmmPass& pass, const float* feature, float* posterior,
                             float* scratch, std::size_t blocks) noexcept {
    const std::size_t J = model.component_count;
    const std::size_t block = ModelView::gmm_block;
    // The log joints, the start's block first; a block that stops early
    // writes −infinity, whose exp is the 0 its own would have given. The
    // blocks come in rotated order, so equal peaks go to the lower index.
    float peak = pass.peak;
    std::size_t best = pass.best;
    std::size_t n = pass.done, first = pass.first;
    for (std::size_t taken = 0; n < J && !pass.failed && (taken < blocks || taken == 0); ++taken) {
        std::size_t lanes = model.gmm_block_lanes(first);
        float q[ModelView::gmm_block * (ACTIONSTRING_DETAIL_WIDE_LANES == 8 ? 2 : 1)];  // a pair with AVX2
        bool computed = false;
#if ACTIONSTRING_DETAIL_WIDE_LANES == 8
        // With AVX2, this block and the next together when both are whole and
        // the next comes next in the rotated order: the same distances, the same order.
        if (model.covariance == Covariance::full && first + 2 * block <= J && first + block != pass.start) {
            lanes = 2 * block;
            computed = detail::gmm_block_distances<2 * ModelView::gmm_block>(model, first, feature, scratch, q, &peak);
        } else
#endif
        {
            computed = detail::gmm_distances(model, first, feature, scratch, q, &peak);
        }
        if (!computed) {
            for (std::size_t l = 0; l < lanes; ++l) posterior[first + l] = -detail::infinity();
        } else {
            for (std::size_t l = 0; l < lanes; ++l) {
                const std::size_t j = first + l;
                const float value = detail::gmm_log_joint_of(model, j, q[l]);
                if (detail::is_nan(value)) pass.failed = true;
                posterior[j] = value;
                if (value > peak || (value == peak && j < best)) peak = value, best = j;
            }
        }
        n += lanes < block ? block : lanes;
        first += lanes < block ? block : lanes;
        if (first >= J) first = 0;
    }
    pass.peak = peak;
    pass.best = best;
    pass.done = n < J ? n : J;
    pass.first = first;
    return pass.done < J && !pass.failed;
}

/// Ends a pass whose blocks are all taken: the posteriors from the log joints.
/// @return as gmm_posterior()'s
inline Status gmm_pass_finish(const ModelView& model, GmmPass& pass, float* posterior, float* log_likelihood = nullptr,
                              std::size_t* most_probable = nullptr) noexcept {
    const std::size_t J = model.component_count;
    if (pass.failed || !detail::is_finite(pass.peak)) return Status::pose_out_of_range;
    const float peak = pass.peak;
    float sum = 0.0f;
    for (std::size_t j = 0; j < J; ++j) {
        posterior[j] = detail::exp_portable(posterior[j] - peak);
        sum += posterior[j];
    }
    // sum ≥ 1: the peak term is exp(0).
    const float inverse = 1.0f / sum;
    for (std::size_t j = 0; j < J; ++j) posterior[j] *= inverse;
    if (log_likelihood != nullptr) *log_likelihood = peak + detail::log_portable(sum);
    if (most_probable != nullptr) *most_probable = pass.best;
    return Status::ok;
}

/// The pose feature t = [p(1|z) … p(J|z)] (paper eq. 5).
///
/// Always sums to 1 and is never all zero: far from every key-pose the nearest
/// component (in likelihood) takes the mass instead of every term underflowing.
/// Components whose posterior underflows to 0 may be left before their distance
/// is finished (gmm.hpp's blocks): the result has the bits of the full
/// computation, only sooner (for features within the range that
/// gmm_is_overflow_safe() vouches for, which normalize_pose() keeps poses in;
/// beyond it, where a distance's later terms would overflow into NaN, a block
/// that stopped early gives 0 where the full sum would have failed).
///
/// @param feature         feature_dim floats; read only during the call
/// @param posterior       receives component_count floats (caller-owned)
/// @param scratch         gmm_scratch_floats(model) floats (caller-owned)
/// @param log_likelihood  if not null, receives log p(z) under the mixture
/// @param most_probable   if not null: on entry, the component whose block is
///                        computed first (the last frame's most probable one
///                        finds the peak early, so more blocks stop early; any
///                        value gives the same result); on return, this
///                        feature's most probable component (the first of equals)
/// @return ok, invalid_argument (a null pointer), or pose_out_of_range when
///         no likelihood is finite in float
inline Status gmm_posterior(const ModelView& model, const float* feature, float* posterior, float* scratch,
                            float* log_likelihood = nullptr, std::size_t* most_probable = nullptr) noexcept {
    if (feature == nullptr || posterior == nullptr || scratch == nullptr) return Status::invalid_argument;
    GmmPass pass;
    gmm_pass_begin(model, pass, most_probable != nullptr ? *most_probable : 0);
    gmm_pass_advance(model, pass, feature, posterior, scratch, model.component_count);
    return gmm_pass_finish(model, pass, posterior, log_likelihood, most_probable);
}

}  // namespace actionstring
