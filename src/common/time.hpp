// actionstring host library — the one conversion between seconds (host files)
// and microseconds (the runtime's clock).
#pragma once

#include <cmath>
#include <cstdint>

namespace actionstring {
namespace host {

/// Seconds to the runtime's microseconds, rounded to the nearest.
inline std::int64_t seconds_to_us(double seconds) { return static_cast<std::int64_t>(std::llround(seconds * 1e6)); }

/// The runtime's microseconds to seconds.
inline double us_to_seconds(std::int64_t us) { return static_cast<double>(us) * 1e-6; }

}  // namespace host
}  // namespace actionstring
