// actionstring port — POSIX hosts: clock, log and assert hooks.
//
// Every port header gives the same four hooks, so code written against them
// (benchmarks, the replay in port/firmware) builds unchanged for each target:
//   monotonic_ns()  time in nanoseconds, arbitrary origin
//   cycle_count()   the finest counter the platform has (here: nanoseconds)
//   log_write()     writes text as is (no newline added)
//   fail()          reports a broken invariant and ends the program
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace actionstring {
namespace port {

/// Name of this port, for reports.
inline const char* name() noexcept { return "posix"; }

/// Monotonic time in nanoseconds (arbitrary origin).
inline std::int64_t monotonic_ns() noexcept {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

/// On a host the finest counter is the monotonic clock.
inline std::uint64_t cycle_count() noexcept { return static_cast<std::uint64_t>(monotonic_ns()); }

/// Writes a NUL-terminated string to standard output as is.
inline void log_write(const char* text) noexcept { std::fputs(text, stdout); }

/// Reports a broken invariant on standard error and aborts.
[[noreturn]] inline void fail(const char* what, const char* file, int line) noexcept {
    std::fflush(stdout);
    std::fprintf(stderr, "%s:%d: %s\n", file, line, what);
    std::abort();
}

}  // namespace port
}  // namespace actionstring

/// Checks an invariant in port-level code (the runtime itself reports by status).
#define ACTIONSTRING_PORT_ASSERT(condition) \
    ((condition) ? static_cast<void>(0)     \
                 : ::actionstring::port::fail("assertion failed: " #condition, __FILE__, __LINE__))
