// actionstring — small numeric helpers shared by the runtime stages.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace actionstring {
namespace detail {

constexpr float infinity() noexcept { return std::numeric_limits<float>::infinity(); }

// Bit tests rather than std::isfinite so the checks survive -ffinite-math-only,
// which a firmware build may turn on for speed elsewhere in the image.
inline bool is_finite(float value) noexcept {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return (bits & 0x7F800000u) != 0x7F800000u;
}

inline bool is_nan(float value) noexcept {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return (bits & 0x7F800000u) == 0x7F800000u && (bits & 0x007FFFFFu) != 0u;
}

}  // namespace detail
}  // namespace actionstring
