// actionstring port — POSIX hosts: monotonic clock for timing and timestamps.
#pragma once

#include <chrono>
#include <cstdint>

namespace actionstring {
namespace port {

/// Monotonic time in nanoseconds (arbitrary origin).
inline std::int64_t monotonic_ns() noexcept {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace port
}  // namespace actionstring
