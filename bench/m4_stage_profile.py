#!/usr/bin/env python3
"""Instructions the replay firmware executes, by runtime stage, under QEMU.

QEMU's execution trace names the function of every translated block it runs
(`-d exec,nochain,in_asm`: each block's instructions once, then one line per
execution). This script counts instructions per function from such a trace and
groups the runtime's functions into its stages, per frame and per character of
the replayed stream (the firmware prints both counts at its end).

    qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \\
        -semihosting-config enable=on,target=native -icount shift=0 \\
        -kernel build/release/tests/firmware/cortex_m4/actionstring_replay.elf \\
        -d exec,nochain,in_asm -D /tmp/trace.log > /tmp/replay.out
    python3 bench/m4_stage_profile.py /tmp/trace.log /tmp/replay.out

The trace of the CTest stream is about 1 GB and takes a minute to write. The
"per character" is a stage's whole cost divided by the characters: the cost of
one character for the stages that run per character (GMM, segmenter), while
the per-frame stages (normalisation) are read per frame. The firmware replays
the stream twice (as a device runs it, then with the work spread over the
frames, `spread:` in its output), and both passes are averaged. The figures include
everything a stage's functions do, and what the
compiler inlined into them (the annotator inlines the tree descent into the
encoder's character step, for instance); the harness (reading the stream,
printing labels, the calibration loop) is reported apart and is not runtime
cost.
"""
import collections
import re
import sys

# Stage of a (demangled-ish) function name: the first pattern that matches.
STAGES = [
    ("model validation (once, at init)", r"validate|all_within|overflow_safe|names_ok|symmetric"),
    ("GMM posterior", r"gmm_"),
    ("PCA projection (detail::axpy)", r"6detail5axpy|axpy"),
    ("pose normalisation", r"normalize_pose"),
    ("velocity ring", r"MotionRing"),
    ("tree descent", r"node_distances|descend|tree_"),
    ("string encoder (sampling, projection call)", r"StringEncoder|project_pose"),
    ("segmenter", r"ActionSegmenter"),
    ("window matcher and classification", r"WindowMatcher|classify|string_distance"),
    ("annotator (events, labels)", r"Annotator|EventTracker"),
    ("exp / log", r"exp_portable|log_portable"),
    ("harness (stream, printing, calibration)", r"^main$|Line|semihost|_write|memset|memcpy|__aeabi|__udiv"),
]


def stage_of(symbol):
    for name, pattern in STAGES:
        if re.search(pattern, symbol):
            return name
    return "other"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    block_length = {}  # start address -> instructions in the block
    block_symbol = {}
    executions = collections.Counter()
    symbol = None
    start = None
    with open(sys.argv[1], errors="replace") as trace:
        for line in trace:
            if line.startswith("IN: "):
                symbol, start = line[4:].strip(), None
            elif line.startswith("0x") and symbol is not None:
                address = int(line.split(":", 1)[0], 16)
                if start is None:
                    start = address
                    block_length[start] = 0
                    block_symbol[start] = symbol
                block_length[start] += 1
            elif line.startswith("Trace "):
                symbol, start = None, None
                match = re.search(r"\[[0-9a-f]+/([0-9a-f]+)/", line)
                if match:
                    executions[int(match.group(1), 16)] += 1
    output = open(sys.argv[2], errors="replace").read()
    end = re.search(r"^end: frames (\d+) .*characters (\d+)", output, re.M)
    if not end:
        sys.exit(f"{sys.argv[2]}: no 'end: frames N ... characters N' line (did the firmware finish?)")
    frames, characters = int(end.group(1)), int(end.group(2))
    # The firmware replays the stream once as a device runs it and, when it
    # prints a "spread:" line, once more with the work spread over frames: the
    # trace holds every pass, so the counts are per pass of each.
    passes = 1 + len(re.findall(r"^spread: ", output, re.M))
    frames, characters = frames * passes, characters * passes

    by_stage = collections.Counter()
    by_symbol = collections.Counter()
    for address, count in executions.items():
        instructions = count * block_length.get(address, 0)
        by_symbol[block_symbol.get(address, "?")] += instructions
        by_stage[stage_of(block_symbol.get(address, "?"))] += instructions
    total = sum(by_stage.values())
    runtime = total - by_stage["harness (stream, printing, calibration)"] - by_stage["model validation (once, at init)"]
    print(f"{frames} frames, {characters} characters ({passes} passes of the stream); {total} instructions traced, "
          f"{runtime} in the runtime's per-frame work\n")
    print("| stage | instructions | per frame | per character |")
    print("|---|---:|---:|---:|")
    for stage, instructions in by_stage.most_common():
        print(f"| {stage} | {instructions} | {instructions / frames:.0f} | {instructions / characters:.0f} |")
    print("\nFunctions (the 15 largest):\n")
    for name, instructions in by_symbol.most_common(15):
        print(f"  {instructions / characters:9.0f} per character  {name}")


if __name__ == "__main__":
    main()
