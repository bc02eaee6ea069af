#!/bin/sh
# Instructions per frame of the annotator with the committed model, counted by
# callgrind over one pass of the hdm05/val.tsv stream (repeatable on a noisy machine).
#   bench/callgrind_frame.sh BUILD_DIR      (a Release build with the benchmarks)
set -eu
build=${1:-build/release}
bench=$build/bench/actionstring_frame_latency
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$out/callgrind.out" --collect-atstart=no \
    --toggle-collect='*callgrind_pass*' "$bench" --callgrind-pass >"$out/stdout" 2>"$out/stderr" ||
    { cat "$out/stderr"; exit 1; }
frames=$(sed -n 's/^frames \([0-9]*\) characters \([0-9]*\)$/\1/p' "$out/stdout")
characters=$(sed -n 's/^frames \([0-9]*\) characters \([0-9]*\)$/\2/p' "$out/stdout")
total=$(sed -n 's/^totals: *\([0-9]*\).*/\1/p' "$out/callgrind.out")
echo "callgrind: $total instructions for $frames frames ($characters characters):" \
     "$((total / frames)) per frame on average ($((total / characters)) per character: the pass divided by its characters)"
