// actionstring — y += Σ columns · scalars, four columns per pass over y.
//
// The projection accumulates a vector column by column: y[r] += a_c[r] · x_c
// for c = 0, 1, …. One pass per column loads and stores every y[r] once per
// column; four columns per pass keep y[r] in a register across them, which on
// a Cortex-M4 (no SIMD, one load per float) cuts the instructions per
// multiply-add from about six to three.
//
// Every y[r] still adds its terms in increasing c, each rounded as before
// (a product, then a sum: the runtime is built without contraction into fused
// multiply-adds), so the result is bit-identical to one column at a time.
#pragma once

#include <cstddef>

#include "actionstring/detail/lanes.hpp"
#include "actionstring/detail/math.hpp"

namespace actionstring {
namespace detail {

// Without SIMD (a Cortex-M4), never inlined: inside its caller (the encoder's
// character step, with the projection inlined) the four column pointers no
// longer fit the registers and two are spilled to the stack on every row (15
// instructions per row against 10 here); the call costs a few instructions per
// block. With SSE the inlined loop is the faster one (40 ns a projection,
// measured), so the host keeps it inline.
#if ACTIONSTRING_DETAIL_LANES == 0
#define ACTIONSTRING_DETAIL_AXPY4_INLINE ACTIONSTRING_DETAIL_NEVER_INLINE
#else
#define ACTIONSTRING_DETAIL_AXPY4_INLINE
#endif

/// y[r] += a0[r]·x0, then a1[r]·x1, a2[r]·x2, a3[r]·x3, for r < n.
ACTIONSTRING_DETAIL_AXPY4_INLINE inline void axpy4(float* y, std::size_t n, const float* a0, float x0,
                                                   const float* a1, float x1, const float* a2, float x2,
                                                   const float* a3, float x3) noexcept {
    if (n == 0) return;
    // Tested at the bottom: one branch per row.
    const float* const end = y + n;
    do {
        float sum = *y;
        sum += *a0++ * x0;
        sum += *a1++ * x1;
        sum += *a2++ * x2;
        sum += *a3++ * x3;
        *y++ = sum;
    } while (y != end);
}

/// y[r] += a[r]·x for r < n.
inline void axpy1(float* y, std::size_t n, const float* a, float x) noexcept {
    for (std::size_t r = 0; r < n; ++r) y[r] += a[r] * x;
}

}  // namespace detail
}  // namespace actionstring
