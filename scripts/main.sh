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
rows=()
online_rows=()
# One evaluation: train, generate the header, build the evaluator against it, evaluate.
# The table is read from the JSON each tool writes; the text reports are for reading.
#   run NAME TITLE TRAIN EVAL CONFIG(or "") [eval options...]
run() {
    local name=$1 title=$2 train=$3 eval=$4 config=$5
    shift 5
    echo "== $title"
    local config_args=()
    [ -n "$config" ] && config_args=(--config "$config")
    "$cli" train --clips "$train" "${config_args[@]}" --out "$out/$name.model" --json "$out/${name}_train.json" \
        > "$out/${name}_train.txt" 2>/dev/null
    "$cli" codegen "$out/$name.model" --out "$out/${name}_model.hpp" --namespace "actionstring_$name"
    "$cli" eval --model "$out/$name.model" --clips "$eval" --train "$train" --online \
        --json "$out/${name}_eval.json" --report "$out/${name}_report" "$@" > "$out/${name}_eval.txt"
    header_eval "$name" "$eval" > "$out/${name}_header_eval.json"
    grep -E "^(representatives|tables|  total)" "$out/${name}_train.txt"
    grep -E "^  (action strings|1-NN|DTW)|^  (segmenter|paper)|^annotator|^online|outside every" "$out/${name}_eval.txt"
    local header_accuracy
    header_accuracy=$(jq -r '.clip_accuracy' "$out/${name}_header_eval.json")
    echo "  evaluator built against the generated header: clip accuracy $header_accuracy"
    # One table row: | title | clip (95% interval) | header | all strings | PCA-only | DTW (McNemar p against
    # the model on the same clips) | settled | window | bytes | ns | s |
    rows+=("$(jq -r -n --arg title "$title" \
        --slurpfile e "$out/${name}_eval.json" --slurpfile t "$out/${name}_train.json" \
        --slurpfile h "$out/${name}_header_eval.json" '
        def base(method): [$e[0].baselines[] | select(.method == method)][0];
        [$title, $e[0].clip_accuracy, $e[0].clip_accuracy_ci95[0], $e[0].clip_accuracy_ci95[1], $h[0].clip_accuracy,
         base("1-NN over all training strings").clip_accuracy, base("1-NN, PCA-only characters (no GMM)").clip_accuracy,
         base("DTW 1-NN on normalised poses").clip_accuracy, base("DTW 1-NN on normalised poses").paired_with_model.mcnemar_p,
         $e[0].online.settled.frame_accuracy, $e[0].online.latest_window.frame_accuracy,
         $t[0].table_bytes, $e[0].frame_time_ns.median, $t[0].stage_seconds.total] | @tsv' |
        awk -F'\t' '{ printf "| %s | %.3f (%.3f–%.3f) | %.3f | %.3f | %.3f | %.3f (p %.3f) | %.3f | %.3f | %d | %.0f | %.2f |", \
                       $1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14 }')")
    # One row of the online table: the streams as the field judges them, beside the trivial baseline.
    online_rows+=("$(jq -r -n --arg title "$title" --slurpfile e "$out/${name}_eval.json" '
        $e[0].online as $o | $o.settled as $s |
        [$title, $o.streams, $s.no_action_frames, $s.unknown_everywhere_accuracy,
         $s.frame_accuracy - $s.unknown_everywhere_accuracy, $s.gain_over_unknown_everywhere_ci95[0],
         $s.gain_over_unknown_everywhere_ci95[1], $s.frame_accuracy, $s.frame_accuracy_ci95[0],
         $s.frame_accuracy_ci95[1], $s.action_frame_accuracy, $s.no_action_accuracy, $s.frame_f1, $s.segment_f1,
         $s.segment_f1_ci95[0], $s.segment_f1_ci95[1], $s.events.f1, $s.events.segment_f1, $s.events.segment_f1_ci95[0],
         $s.events.segment_f1_ci95[1], $s.events.detection_latency_s, $s.events.start_error_s, $s.events.end_error_s,
         $s.events.false_events_per_min, $s.events.false_events_per, $o.live.frame_accuracy,
         $o.latest_window.frame_accuracy] | @tsv' |
        awk -F'\t' '{ unknown = sprintf("%.3f", $4)
                       # With stretches of no action: the settled labels lead over saying nothing, paired.
                       if ($3 > 0) unknown = sprintf("%.3f (lead %+.3f, %+.3f to %+.3f)", $4, $5, $6, $7)
                       printf "| %s | %s | %s | %.3f (%.3f–%.3f; %.3f / %.3f) | %.3f | %.3f (%.3f–%.3f) | %.3f (%.3f, %.3f–%.3f) | %.2f | %.2f / %.2f | %.2f per %s | %.3f | %.3f |", \
                       $1, $2, unknown, $8, $9, $10, $11, $12, $13, $14, $15, $16, $17, $18, $19, $20, $21, $22, $23, $24, $25, $26, $27 }')")
    echo
}

# The generated header compiled into a program that classifies the list's clips with
# the constexpr tables (no artifact loaded): the result must equal the artifact's.
# Prints the evaluator's JSON.
header_eval() {
    local name=$1 list=$2 build="$out/${name}_header_eval"
    cmake -S "$root/codegen/header_eval" -B "$build" -DCMAKE_BUILD_TYPE=Release \
        -DACTIONSTRING_MODEL_HEADER="$out/${name}_model.hpp" -DACTIONSTRING_MODEL_NAMESPACE="actionstring_$name" \
        >"$build.log" 2>&1 || { echo "header evaluator: configure failed ($build.log)" >&2; return 1; }
    cmake --build "$build" -j"$(nproc 2>/dev/null || echo 2)" >>"$build.log" 2>&1 ||
        { echo "header evaluator: build failed ($build.log)" >&2; return 1; }
    "$build/actionstring_header_eval" "$list"
}

run hdm05 "HDM05 val (actor mm), CV-chosen model" "$data/hdm05/train.tsv" "$data/hdm05/val.tsv" "$root/models/hdm05-accurate.config"
run hdm05_firmware "HDM05 val, firmware model (the committed header)" "$data/hdm05/train.tsv" "$data/hdm05/val.tsv" "$root/models/hdm05.config"
run hdm05_gmm "HDM05 val, the paper's GMM feature (J = 20)" "$data/hdm05/train.tsv" "$data/hdm05/val.tsv" "$root/models/hdm05-gmm.config"
if [ -f "$data/msr-action3d/train.tsv" ]; then
    run msr "MSR Action3D test (even subjects), CV-chosen settings" "$data/msr-action3d/train.tsv" "$data/msr-action3d/test.tsv" \
        "$root/models/msr.config"
fi
if [ -f "$data/utkinect/actionLabel.txt" ]; then
    # Cut intervals of s01–s03 train; s04–s06's whole recordings are streamed, and
    # frames outside every labelled interval should come out unknown.
    "$cli" interval-list --utkinect "$data/utkinect/actionLabel.txt" --subjects s01,s02,s03 --out "$out/utkinect_train.tsv" >/dev/null
    "$cli" interval-list --utkinect "$data/utkinect/actionLabel.txt" --subjects s04,s05,s06 --out "$out/utkinect_test.tsv" >/dev/null
    run utkinect "UTKinect s04–s06 whole recordings (clips: their intervals)" "$out/utkinect_train.tsv" "$out/utkinect_test.tsv" \
        "$root/models/utkinect.config"
fi

echo "| evaluation | clip accuracy (95% interval) | same, generated header | 1-NN all strings | 1-NN PCA-only characters | DTW 1-NN (McNemar p against the model) | online frames (settled) | online (paper's window rule) | model table bytes | per frame median | training |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
printf '%s\n' "${rows[@]}"
echo
echo "Online (streamed frame by frame; settled labels and action events; no-action accuracy is meaningless on concatenated clips, which have none):"
echo
echo "Intervals are 95%, resampling the true actions and stretches of no action (the streams' people stay the same)."
echo
echo "| evaluation | streams | unknown everywhere (the settled labels' lead, 95% interval) | settled frame accuracy (95% interval; in action / no action) | frame F1 | segment F1 (95% interval) | event F1 (as segments, IoU ≥ 0.5: F1, 95% interval) | detection latency (s) | start / end error (s) | false events | live labels | paper's window rule |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|"
printf '%s\n' "${online_rows[@]}"
echo
echo "Reports (report.md with SVG pictures), models, JSON and generated headers are in $out"
