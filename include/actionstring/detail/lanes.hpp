// actionstring — four float lanes for the segmenter's cells and the GMM's components, where the target has them.
//
// The segmenter's new cells depend only on the previous step's cells, so four
// neighbouring cells of a representative are computed at once. Only the
// operations the recurrence needs are here, each the exact lane-wise twin of
// its scalar expression, so a vector block and the scalar loop give the same
// bits (a comparison selects, an addition rounds once, no fused multiply-add):
//
//   less(a, b)            a < b per lane (false when either is NaN)
//   select(mask, a, b)    mask ? a : b, bit for bit (costs and 32-bit starts alike)
//   minimum(a, b)         a < b ? a : b (SSE's MINPS is defined exactly so)
//   all_less(a, b)        a < b in every lane
//   transpose(a, b, c, d) four rows of lanes to four columns
//
// The GMM (gmm.hpp) puts four components in the lanes: a product, then a sum,
// each rounded once per lane as the scalar loop rounds it. The exemplars
// (exemplars.hpp) put a centre's four partial sums in them, which the scalar
// loop keeps as four chains.
//
// ACTIONSTRING_DETAIL_LANES is 4 with SSE2 (every x86-64 compiler) and 0
// elsewhere: a Cortex-M4 has no float SIMD, and there the scalar loop, tuned
// for its registers, does every cell. Define ACTIONSTRING_NO_SIMD to measure
// or test the scalar path on a host.
#pragma once

#include <cstddef>
#include <cstdint>

#if !defined(ACTIONSTRING_NO_SIMD) && (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#include <emmintrin.h>
#define ACTIONSTRING_DETAIL_LANES 4
#else
#define ACTIONSTRING_DETAIL_LANES 0
#endif

// Eight lanes as well when the compiler targets AVX2 (-mavx2, -march=x86-64-v3):
// the segmenter then takes eight cells a step and the GMM eight components.
// The arithmetic per lane is the same, so the bits are too. Without it (the
// x86-64 baseline) the four-lane code above is all there is.
#if ACTIONSTRING_DETAIL_LANES == 4 && defined(__AVX2__)
#include <immintrin.h>
#define ACTIONSTRING_DETAIL_WIDE_LANES 8
#else
#define ACTIONSTRING_DETAIL_WIDE_LANES 0
#endif

namespace actionstring {
namespace detail {

#if ACTIONSTRING_DETAIL_LANES == 4

struct Lanes {
    __m128 v;
};
struct LaneMask {
    __m128 v;
};

inline Lanes load_lanes(const float* p) noexcept { return Lanes{_mm_loadu_ps(p)}; }
// 32-bit integers travel in float registers as bits; select() moves bits only.
inline Lanes load_lanes(const std::uint32_t* p) noexcept {
    return Lanes{_mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)))};
}
inline void store_lanes(float* p, Lanes a) noexcept { _mm_storeu_ps(p, a.v); }
inline void store_lanes(std::uint32_t* p, Lanes a) noexcept {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm_castps_si128(a.v));
}
inline Lanes broadcast(float x) noexcept { return Lanes{_mm_set1_ps(x)}; }
inline Lanes broadcast_bits(std::uint32_t x) noexcept {
    return Lanes{_mm_castsi128_ps(_mm_set1_epi32(static_cast<int>(x)))};
}
/// {x0, x1, x2, x3}, lane 0 first (lowest address when stored).
inline Lanes lanes_of(float x0, float x1, float x2, float x3) noexcept { return Lanes{_mm_setr_ps(x0, x1, x2, x3)}; }
inline Lanes operator+(Lanes a, Lanes b) noexcept { return Lanes{_mm_add_ps(a.v, b.v)}; }
inline Lanes operator-(Lanes a, Lanes b) noexcept { return Lanes{_mm_sub_ps(a.v, b.v)}; }
inline Lanes operator*(Lanes a, Lanes b) noexcept { return Lanes{_mm_mul_ps(a.v, b.v)}; }
inline LaneMask less(Lanes a, Lanes b) noexcept { return LaneMask{_mm_cmplt_ps(a.v, b.v)}; }
inline Lanes select(LaneMask m, Lanes a, Lanes b) noexcept {
    return Lanes{_mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v))};
}
inline Lanes minimum(Lanes a, Lanes b) noexcept { return Lanes{_mm_min_ps(a.v, b.v)}; }
/// Whether a < b in every lane (false when any lane is NaN).
inline bool all_less(Lanes a, Lanes b) noexcept { return _mm_movemask_ps(_mm_cmplt_ps(a.v, b.v)) == 0xF; }
/// {fill[0], a[0], a[1], a[2]}: a's lanes one place up, fill's first lane entering
/// (bits moved, not rounded: costs and 32-bit starts alike).
inline Lanes lanes_up1(Lanes a, Lanes fill) noexcept {
    const __m128 fill_and_first = _mm_shuffle_ps(fill.v, a.v, _MM_SHUFFLE(0, 0, 0, 0));  // f0 f0 a0 a0
    return Lanes{_mm_shuffle_ps(fill_and_first, a.v, _MM_SHUFFLE(2, 1, 2, 0))};
}
/// {fill[0], fill[1], a[0], a[1]}: a's lanes two places up, fill's first two entering.
inline Lanes lanes_up2(Lanes a, Lanes fill) noexcept {
    return Lanes{_mm_shuffle_ps(fill.v, a.v, _MM_SHUFFLE(1, 0, 1, 0))};
}
/// Rows to columns: a, b, c, d become {a0, b0, c0, d0}, {a1, b1, c1, d1}, … (bits
/// moved, not rounded).
inline void transpose(Lanes& a, Lanes& b, Lanes& c, Lanes& d) noexcept { _MM_TRANSPOSE4_PS(a.v, b.v, c.v, d.v); }
/// The smallest lane (exact: the minimum of finite values or infinities does not round).
inline float smallest_lane(Lanes a) noexcept {
    const __m128 pairs = _mm_min_ps(a.v, _mm_movehl_ps(a.v, a.v));
    return _mm_cvtss_f32(_mm_min_ss(pairs, _mm_shuffle_ps(pairs, pairs, 1)));
}

// The loads of a lane count, for code written once for four and eight lanes.
template <std::size_t L>
struct LaneOps;
template <>
struct LaneOps<4> {
    using V = Lanes;
    static V load(const float* p) noexcept { return load_lanes(p); }
    static V load(const std::uint32_t* p) noexcept { return load_lanes(p); }
    static V broadcast(float x) noexcept { return detail::broadcast(x); }
    /// {table[index[0]], …, table[index[3]]}
    static V gather(const float* table, const std::uint16_t* index) noexcept {
        return lanes_of(table[index[0]], table[index[1]], table[index[2]], table[index[3]]);
    }
};

#endif

#if ACTIONSTRING_DETAIL_WIDE_LANES == 8

// The eight-lane twins of the operations above (AVX2), for the same callers.
struct Lanes8 {
    __m256 v;
};
struct LaneMask8 {
    __m256 v;
};

inline Lanes8 load_lanes8(const float* p) noexcept { return Lanes8{_mm256_loadu_ps(p)}; }
inline Lanes8 load_lanes8(const std::uint32_t* p) noexcept {
    return Lanes8{_mm256_castsi256_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)))};
}
inline void store_lanes(float* p, Lanes8 a) noexcept { _mm256_storeu_ps(p, a.v); }
inline void store_lanes(std::uint32_t* p, Lanes8 a) noexcept {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), _mm256_castps_si256(a.v));
}
inline Lanes8 broadcast8(float x) noexcept { return Lanes8{_mm256_set1_ps(x)}; }
/// {table[index[0]], …, table[index[7]]}, by eight scalar loads: VGATHERDPS was
/// slower than them on the AMD processor measured.
inline Lanes8 gather8(const float* table, const std::uint16_t* index) noexcept {
    return Lanes8{_mm256_setr_ps(table[index[0]], table[index[1]], table[index[2]], table[index[3]], table[index[4]],
                                 table[index[5]], table[index[6]], table[index[7]])};
}
inline Lanes8 operator+(Lanes8 a, Lanes8 b) noexcept { return Lanes8{_mm256_add_ps(a.v, b.v)}; }
inline Lanes8 operator-(Lanes8 a, Lanes8 b) noexcept { return Lanes8{_mm256_sub_ps(a.v, b.v)}; }
inline Lanes8 operator*(Lanes8 a, Lanes8 b) noexcept { return Lanes8{_mm256_mul_ps(a.v, b.v)}; }
// _CMP_LT_OQ: false when either is NaN, as the scalar a < b.
inline LaneMask8 less(Lanes8 a, Lanes8 b) noexcept { return LaneMask8{_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
inline Lanes8 select(LaneMask8 m, Lanes8 a, Lanes8 b) noexcept { return Lanes8{_mm256_blendv_ps(b.v, a.v, m.v)}; }
// VMINPS is a < b ? a : b per lane, as MINPS.
inline Lanes8 minimum(Lanes8 a, Lanes8 b) noexcept { return Lanes8{_mm256_min_ps(a.v, b.v)}; }
inline bool all_less(Lanes8 a, Lanes8 b) noexcept {
    return _mm256_movemask_ps(_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)) == 0xFF;
}
inline float smallest_lane(Lanes8 a) noexcept {
    return smallest_lane(minimum(Lanes{_mm256_castps256_ps128(a.v)}, Lanes{_mm256_extractf128_ps(a.v, 1)}));
}
template <>
struct LaneOps<8> {
    using V = Lanes8;
    static V load(const float* p) noexcept { return load_lanes8(p); }
    static V load(const std::uint32_t* p) noexcept { return load_lanes8(p); }
    static V broadcast(float x) noexcept { return broadcast8(x); }
    static V gather(const float* table, const std::uint16_t* index) noexcept { return gather8(table, index); }
};

#endif

}  // namespace detail
}  // namespace actionstring
