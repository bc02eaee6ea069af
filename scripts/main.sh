#!/usr/bin/env bash
# The main job: installs what is missing, builds the tools and runs them.
# Until the trainer and evaluator land, that is the synthetic streaming demo;
# extra arguments go to 'actionstring demo' (try --help).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=deps.sh
source "$root/scripts/deps.sh"
ensure_packages "${ACTIONSTRING_HOST_PACKAGES[@]}"
dir="$root/build/main"
cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DACTIONSTRING_BUILD_TESTS=OFF >/dev/null
cmake --build "$dir" -j"$(nproc 2>/dev/null || echo 2)" --target actionstring_cli >/dev/null
"$dir/codegen/actionstring" demo "$@"
