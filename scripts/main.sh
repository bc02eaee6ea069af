#!/usr/bin/env bash
# The main job: installs what is missing, builds the tools, then — with the
# datasets present — trains on HDM05 and MSR Action3D, generates the model
# header, and evaluates clips (beside baselines) and online streams.
# Without data it says how to point at it and runs the synthetic demo.
#   bash scripts/main.sh            the job
#   bash scripts/main.sh --demo     the synthetic streaming demo only
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=deps.sh
source "$root/scripts/deps.sh"
ensure_packages "${ACTIONSTRING_HOST_PACKAGES[@]}"
dir="$root/build/main"
cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DACTIONSTRING_BUILD_TESTS=OFF >/dev/null
cmake --build "$dir" -j"$(nproc 2>/dev/null || echo 2)" --target actionstring_cli >/dev/null
cli="$dir/codegen/actionstring"

data=${ACTIONSTRING_DATA:-$root/../shared/data}
if [ "${1:-}" = "--demo" ] || [ ! -f "$data/hdm05/train.tsv" ]; then
    if [ "${1:-}" != "--demo" ]; then
        echo "No datasets at $data (expected hdm05/train.tsv)."
        echo "Set ACTIONSTRING_DATA=/path/to/datasets to train and evaluate; running the synthetic demo instead."
        echo
    fi
    shift || true
    exec "$cli" demo "$@"
fi

out="$dir/results"
mkdir -p "$out"
echo "== HDM05 (11 classes, cross-subject: train bd/bk/dg, validate mm)"
"$cli" train --clips "$data/hdm05/train.tsv" --config "$root/models/hdm05.config" --out "$out/hdm05.model" \
    > "$out/hdm05_train.txt"
"$cli" codegen "$out/hdm05.model" --out "$out/hdm05_model.hpp" --namespace actionstring_hdm05
"$cli" eval --model "$out/hdm05.model" --clips "$data/hdm05/val.tsv" --train "$data/hdm05/train.tsv" --online \
    --json "$out/hdm05_eval.json" > "$out/hdm05_eval.txt"
grep -E "^(tables|  total)" "$out/hdm05_train.txt"
grep -E "^  (action strings|1-NN|DTW)|^online|^annotator" "$out/hdm05_eval.txt"

if [ -f "$data/msr-action3d/train.tsv" ]; then
    echo
    echo "== MSR Action3D (20 classes, cross-subject: odd subjects train, even test; default settings, not tuned)"
    "$cli" train --clips "$data/msr-action3d/train.tsv" --out "$out/msr.model" > "$out/msr_train.txt"
    "$cli" eval --model "$out/msr.model" --clips "$data/msr-action3d/test.tsv" --train "$data/msr-action3d/train.tsv" \
        --online --json "$out/msr_eval.json" > "$out/msr_eval.txt"
    grep -E "^(tables|  total)" "$out/msr_train.txt"
    grep -E "^  (action strings|1-NN|DTW)|^online|^annotator" "$out/msr_eval.txt"
fi
echo
echo "Full reports, models, JSON and the generated header are in $out"
