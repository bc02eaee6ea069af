// actionstring — library version.
#pragma once

#define ACTIONSTRING_VERSION_MAJOR 0
#define ACTIONSTRING_VERSION_MINOR 1
#define ACTIONSTRING_VERSION_PATCH 0

namespace actionstring {

/// Library version as "major.minor.patch" (static storage).
constexpr const char* version_string() noexcept { return "0.1.0"; }

}  // namespace actionstring
