#!/usr/bin/env bash
# The test command: installs what is missing, then builds and runs every test
# twice — Release with g++ and warnings as errors (with the Python package and
# its pytest suite), and Debug with clang under
# AddressSanitizer + UndefinedBehaviorSanitizer, where each reader is also
# fuzzed for ACTIONSTRING_FUZZ_SECONDS (default 30) seconds.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=deps.sh
source "$root/scripts/deps.sh"
ensure_packages "${ACTIONSTRING_HOST_PACKAGES[@]}"
jobs=$(nproc 2>/dev/null || echo 2)

run_suite() {
    local name=$1; shift
    local dir="$root/build/$name"
    # A build folder configured with other settings is rebuilt from scratch:
    # CMake drops its whole cache when a compiler changes, and the build type with it.
    if [ -f "$dir/CMakeCache.txt" ] && [ "$(cat "$dir/.suite-settings" 2>/dev/null)" != "$*" ]; then
        rm -rf "$dir"
    fi
    echo "== $name: configure and build" >&2
    cmake -S "$root" -B "$dir" -DACTIONSTRING_WARNINGS_AS_ERRORS=ON "$@" >/dev/null
    printf '%s' "$*" >"$dir/.suite-settings"
    cmake --build "$dir" -j"$jobs"
    echo "== $name: tests" >&2
    ctest --test-dir "$dir" --output-on-failure -j"$jobs"
}

start=$(date +%s)
# The Python package is built and tested against Debian's interpreter (its packages are there).
run_suite release -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ -DCMAKE_C_COMPILER=gcc \
    -DACTIONSTRING_BUILD_PYTHON=ON -DPython_EXECUTABLE=/usr/bin/python3
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
    run_suite asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DACTIONSTRING_SANITIZE=ON \
        -DACTIONSTRING_FUZZ=ON -DACTIONSTRING_FUZZ_SECONDS="${ACTIONSTRING_FUZZ_SECONDS:-30}"
echo "actionstring: all test suites passed in $(( $(date +%s) - start )) s" >&2
