#!/usr/bin/env bash
# How the main job's models hold up on recordings unlike the shared datasets':
# each model evaluated again on its held-out list changed as another sensor or
# person would change it (`actionstring eval --perturb`), beside DTW 1-NN on the
# same changed clips. The training clips are never changed. Prints a Markdown
# table per dataset.
#   bash scripts/main.sh && bash scripts/robustness.sh
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=deps.sh
source "$root/scripts/deps.sh"
ensure_packages "${ACTIONSTRING_HOST_PACKAGES[@]}"
dir="$root/build/main"
cli="$dir/codegen/actionstring"
out="$dir/results"
data=${ACTIONSTRING_DATA:-$root/../shared/data}
if [ ! -x "$cli" ] || [ ! -f "$out/hdm05.model" ]; then
    echo "No main-job models in $out: run 'bash scripts/main.sh' first." >&2
    exit 1
fi
mkdir -p "$out/robustness"

# table NAME TITLE TRAIN EVAL RATE [EXTRA...]: one row per perturbation; RATE is another sensor's frame
# rate for that data; EXTRA are further specs (mirror=1 where the classes are not lateral: a
# mirrored grabHighR is a left-handed grab, which HDM05 labels otherwise).
table() {
    local name=$1 title=$2 train=$3 eval=$4 rate=$5
    shift 5
    echo "$title"
    echo
    echo "| evaluated clips | clip accuracy | DTW 1-NN | settled frame accuracy | segment F1 | event F1 |"
    echo "|---|---:|---:|---:|---:|---:|"
    local spec
    for spec in none scale=0.7 scale=1.25 tilt=10 tilt=-10 noise=0.01 noise=0.03 "rate=$rate" jitter=0.01 drop=0.3 "$@"; do
        local json="$out/robustness/${name}_${spec//[=.]/_}.json" perturb=()
        [ "$spec" != none ] && perturb=(--perturb "$spec")
        "$cli" eval --model "$out/$name.model" --clips "$eval" --train "$train" --online "${perturb[@]}" \
            --json "$json" > /dev/null
        jq -r '
            def acc(method): [.baselines[] | select(.method == method) | .clip_accuracy][0];
            [.perturbation, .clip_accuracy, acc("DTW 1-NN on normalised poses"), .online.settled.frame_accuracy,
             .online.settled.segment_f1, .online.settled.events.f1] | @tsv' "$json" |
            awk -F'\t' '{ printf "| %s | %.3f | %.3f | %.3f | %.3f | %.3f |\n", $1, $2, $3, $4, $5, $6 }'
    done
    echo
}

table hdm05 "HDM05 val (actor mm), hdm05-accurate.config, 120 Hz optical" \
    "$data/hdm05/train.tsv" "$data/hdm05/val.tsv" 30
if [ -f "$out/msr.model" ]; then
    table msr "MSR Action3D test, msr.config, 15 Hz Kinect v1" \
        "$data/msr-action3d/train.tsv" "$data/msr-action3d/test.tsv" 30 mirror=1
fi
if [ -f "$out/utkinect.model" ]; then
    table utkinect "UTKinect s04–s06 whole recordings, utkinect.config, 30 Hz Kinect v1" \
        "$out/utkinect_train.tsv" "$out/utkinect_test.tsv" 15 mirror=1
fi
