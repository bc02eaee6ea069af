// actionstring — small numeric helpers shared by the runtime stages.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

// Forces a small helper (a function or a lambda) inline where it sits in a hot
// loop: -Os keeps a helper called from several places out of line, and the
// call then costs more than its body (the segmenter's cells on a Cortex-M4).
// Measured, not assumed: the GMM's four-component packs (gmm.hpp) must be
// inline, or every lane operation becomes a call through the stack. The
// opposite also happens: the projection's column blocks (detail/axpy.hpp),
// inlined into their one caller, run out of the M4's registers, so there they
// are kept calls (ACTIONSTRING_DETAIL_NEVER_INLINE).
#if defined(__GNUC__) || defined(__clang__)
#define ACTIONSTRING_DETAIL_ALWAYS_INLINE __attribute__((always_inline))
#define ACTIONSTRING_DETAIL_NEVER_INLINE __attribute__((noinline))
#else
#define ACTIONSTRING_DETAIL_ALWAYS_INLINE
#define ACTIONSTRING_DETAIL_NEVER_INLINE
#endif

namespace actionstring {
namespace detail {

constexpr float infinity() noexcept { return std::numeric_limits<float>::infinity(); }

/// Smallest power of two ≥ value (value ≥ 1).
constexpr std::size_t next_power_of_two(std::size_t value) noexcept {
    std::size_t power = 1;
    while (power < value) power *= 2;
    return power;
}

inline std::uint32_t to_bits(float value) noexcept {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

// Bit tests rather than std::isfinite so the checks survive -ffinite-math-only,
// which a firmware build may turn on for speed elsewhere in the image.
inline bool is_finite(float value) noexcept { return (to_bits(value) & 0x7F800000u) != 0x7F800000u; }

inline bool is_nan(float value) noexcept {
    const std::uint32_t bits = to_bits(value);
    return (bits & 0x7F800000u) == 0x7F800000u && (bits & 0x007FFFFFu) != 0u;
}

inline float from_bits(std::uint32_t bits) noexcept {
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

// exp_portable(x) is exactly 0 for every x below this (the GMM relies on it to
// leave out components whose posterior is 0 before finishing their distances).
constexpr float exp_underflow_bound = -87.33f;

// exp and log written out in plain float arithmetic. The C libraries' expf and
// logf differ in their last bits (glibc, newlib, MSVC), and a last-bit
// difference in a posterior can move a tree descent across a tie; with these
// every IEEE float target computes the same characters and labels as the host.
// exp is within 2 ulp and log within 3 ulp of the exact result (tests/test_gmm.cpp).
inline float exp_portable(float x) noexcept {
    if (is_nan(x)) return x;
    if (x > 88.72f) return infinity();
    if (x < exp_underflow_bound) return 0.0f;  // below FLT_MIN: flushed, as on FTZ targets
    // x = n·ln2 + r with |r| ≤ ln2/2; ln2 split so n·ln2_hi is exact.
    const float scaled = x * 1.44269504f;
    const int n = static_cast<int>(scaled < 0.0f ? scaled - 0.5f : scaled + 0.5f);
    const float nf = static_cast<float>(n);
    const float r = (x - nf * 0.693145752f) - nf * 1.42860677e-6f;
    // Taylor terms to r^7: the truncation error is below 2^-26 on |r| ≤ 0.35.
    float p = 1.98412698e-4f;
    p = p * r + 1.38888889e-3f;
    p = p * r + 8.33333333e-3f;
    p = p * r + 4.16666667e-2f;
    p = p * r + 1.66666667e-1f;
    p = p * r + 0.5f;
    p = p * r + 1.0f;
    p = p * r + 1.0f;
    // 2^n in two factors so n = 128 (x just below the overflow bound) and
    // n = −126 stay representable.
    const int half = n / 2;
    const float scale_a = from_bits(static_cast<std::uint32_t>(half + 127) << 23);
    const float scale_b = from_bits(static_cast<std::uint32_t>(n - half + 127) << 23);
    return p * scale_a * scale_b;
}

inline float log_portable(float x) noexcept {
    if (is_nan(x) || x < 0.0f) return std::numeric_limits<float>::quiet_NaN();
    if (x == 0.0f) return -infinity();
    if (!is_finite(x)) return x;
    int exponent_bias = 0;
    if (x < 1.17549435e-38f) {  // subnormal: scale into the normal range first
        x *= 8388608.0f;
        exponent_bias = -23;
    }
    const std::uint32_t bits = to_bits(x);
    int exponent = static_cast<int>((bits >> 23) & 0xFFu) - 127 + exponent_bias;
    float m = from_bits((bits & 0x007FFFFFu) | 0x3F800000u);  // [1, 2)
    if (m > 1.41421356f) {
        m *= 0.5f;
        ++exponent;
    }
    // log(m) = 2·atanh(s), s = (m−1)/(m+1), |s| ≤ 0.172: odd series to s^11.
    const float s = (m - 1.0f) / (m + 1.0f);
    const float s2 = s * s;
    float p = 0.0909090909f;
    p = p * s2 + 0.111111111f;
    p = p * s2 + 0.142857143f;
    p = p * s2 + 0.2f;
    p = p * s2 + 0.333333333f;
    p = p * s2 + 1.0f;
    const float e = static_cast<float>(exponent);
    return (e * 1.42860677e-6f + 2.0f * s * p) + e * 0.693145752f;
}

}  // namespace detail
}  // namespace actionstring
