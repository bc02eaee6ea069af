// actionstring port — Cortex-M (ARMv7-M) bare metal: clock, log and assert hooks.
//
// The same hooks as port/posix/actionstring_port.hpp. The clock is SysTick on
// the core clock (cortex_m_board.h: ACTIONSTRING_CORE_CLOCK_HZ), extended to
// 64 bits by its wrap interrupt; the log is ARM semihosting (a debugger or QEMU
// prints it); fail() ends the program through semihosting with a failure code.
#pragma once

#include <cstdint>

#include "cortex_m_board.h"

namespace actionstring {
namespace port {

inline const char* name() noexcept { return "cortex-m"; }

/// Core clock cycles since reset (SysTick, 24 bits extended by its interrupt).
inline std::uint64_t cycle_count() noexcept { return actionstring_board_ticks(); }

/// Monotonic time in nanoseconds since reset.
inline std::int64_t monotonic_ns() noexcept {
    const std::uint64_t ticks = cycle_count();
    constexpr std::uint64_t hz = ACTIONSTRING_CORE_CLOCK_HZ;
    return static_cast<std::int64_t>(ticks / hz * 1000000000u + ticks % hz * 1000000000u / hz);
}

/// Writes a NUL-terminated string through semihosting as is.
inline void log_write(const char* text) noexcept { actionstring_board_write(text); }

/// Reports a broken invariant and stops the program with a failure status.
[[noreturn]] inline void fail(const char* what, const char* file, int line) noexcept {
    // "file:line: what" without printf, which would bring the C library's stdio in.
    char line_text[12] = {};
    char* digit = line_text + sizeof line_text - 1;
    unsigned value = line < 0 ? 0u : static_cast<unsigned>(line);
    do {
        *--digit = static_cast<char>('0' + value % 10u);
        value /= 10u;
    } while (value != 0u && digit > line_text + 1);
    *--digit = ':';
    actionstring_board_write(file);
    actionstring_board_write(digit);
    actionstring_board_write(": ");
    actionstring_board_write(what);
    actionstring_board_write("\n");
    actionstring_board_exit(1);
}

}  // namespace port
}  // namespace actionstring

#define ACTIONSTRING_PORT_ASSERT(condition) \
    ((condition) ? static_cast<void>(0)     \
                 : ::actionstring::port::fail("assertion failed: " #condition, __FILE__, __LINE__))
