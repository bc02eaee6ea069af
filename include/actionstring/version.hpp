// actionstring — library version.
//
// One declaration: CMake's project version and package version file are read
// from these three numbers, the CLI's `version`, the C API's
// actionstring_version() and Python's actionstring.__version__ report them, and
// a test holds pyproject.toml and the Python package's literal to them.
//
// Before 1.0 the minor number changes whenever something built against an
// earlier release could break: the C API's structs or functions, a public
// header's interface, or the model formats a build writes (artifacts of
// earlier versions still read; a blob reads only in a build of its format).
// The patch number changes otherwise. The package version file
// (find_package) accepts the same major and minor only.
#pragma once

#define ACTIONSTRING_VERSION_MAJOR 0
#define ACTIONSTRING_VERSION_MINOR 2
#define ACTIONSTRING_VERSION_PATCH 0

#define ACTIONSTRING_DETAIL_STRINGIFY2(x) #x
#define ACTIONSTRING_DETAIL_STRINGIFY(x) ACTIONSTRING_DETAIL_STRINGIFY2(x)
/// "major.minor.patch" as a string literal.
#define ACTIONSTRING_VERSION_STRING                                                                  \
    ACTIONSTRING_DETAIL_STRINGIFY(ACTIONSTRING_VERSION_MAJOR)                                        \
    "." ACTIONSTRING_DETAIL_STRINGIFY(ACTIONSTRING_VERSION_MINOR) "." ACTIONSTRING_DETAIL_STRINGIFY( \
        ACTIONSTRING_VERSION_PATCH)

namespace actionstring {

/// Library version as "major.minor.patch" (static storage).
constexpr const char* version_string() noexcept { return ACTIONSTRING_VERSION_STRING; }

}  // namespace actionstring
