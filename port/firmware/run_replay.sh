#!/bin/sh
# Builds the replay firmware for QEMU's mps2-an386 (Cortex-M4F) and its host
# twin from one real recording, runs both, and checks that every label line is
# identical; then checks the firmware for heap symbols and reports flash, RAM,
# stack and instructions per frame (and again with the work spread, spread_work:
# the same settled labels, per-frame instructions reported). Twice: with the committed example model
# (models/hdm05_model.hpp, no GMM), and with the paper's GMM model trained here
# from models/hdm05-gmm.config, so the GMM posterior is checked bit for bit on
# the Cortex-M4 too. The report (firmware_report.md) has both.
#   run_replay.sh CLI SOURCE_DIR WORK_DIR [C_API_TEST]
# CLI is a built `actionstring`. C_API_TEST, when given, is tests/c_api's
# program: it replays the same frames through the C API, and its settled labels must
# equal the C++ build's too. Exits 77 (CTest: skipped) when the HDM05
# data is absent; 1 on any mismatch or failure.
set -eu
cli=$1 source=$(cd "$2" && pwd) work=$3 c_api_test=${4:-}
data=${ACTIONSTRING_DATA:-$source/../shared/data}
list=$data/hdm05/val.tsv
if [ ! -f "$list" ]; then
    echo "SKIPPED: $list not found (set ACTIONSTRING_DATA to the datasets folder)"
    exit 77
fi
for tool in arm-none-eabi-g++ arm-none-eabi-nm arm-none-eabi-size qemu-system-arm; do
    command -v "$tool" >/dev/null || { echo "missing $tool: run scripts/deps.sh (bash scripts/test.sh installs it)"; exit 1; }
done
mkdir -p "$work"
work=$(cd "$work" && pwd)

# One clip in seven of the validation list (six actions), at most 5 s each.
stream_table() { "$cli" stream-table --clips "$list" --count 6 --stride 7 --max-seconds 5 "$@"; }
stream_table --out "$work/stream.hpp.new"
cmp -s "$work/stream.hpp.new" "$work/stream.hpp" 2>/dev/null || mv "$work/stream.hpp.new" "$work/stream.hpp"
rm -f "$work/stream.hpp.new"

build() {  # build DIR [cmake args…]
    dir=$1; shift
    cmake -S "$source/port/firmware" -B "$work/$dir" -DACTIONSTRING_REPLAY_STREAM="$work/stream.hpp" "$@" >"$work/$dir.configure.log" 2>&1 ||
        { cat "$work/$dir.configure.log"; exit 1; }
    cmake --build "$work/$dir" >"$work/$dir.build.log" 2>&1 || { cat "$work/$dir.build.log"; exit 1; }
}

# replay NAME WHAT [cmake args…]: both builds of one model, run and compared;
# the outputs are $work/NAME{host,cortex_m4}.{out,labels}.
replay() {
    name=$1 what=$2; shift 2
    build "${name}host" "$@"
    build "${name}cortex_m4" -DCMAKE_TOOLCHAIN_FILE="$source/port/cortex_m/arm-none-eabi.cmake" "$@"
    elf=$work/${name}cortex_m4/actionstring_replay.elf
    "$work/${name}host/actionstring_replay" >"$work/${name}host.out"
    # -icount shift=0: one instruction per nanosecond of virtual time, so SysTick
    # counts instructions (the firmware calibrates this with a loop of known length).
    timeout 300 qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
        -semihosting-config enable=on,target=native -icount shift=0 -kernel "$elf" >"$work/${name}cortex_m4.out" 2>&1 ||
        { echo "$what: the firmware failed under QEMU:"; tail -20 "$work/${name}cortex_m4.out"; exit 1; }
    grep -v '^#' "$work/${name}host.out" >"$work/${name}host.labels"
    grep -v '^#' "$work/${name}cortex_m4.out" >"$work/${name}cortex_m4.labels"
    if ! cmp -s "$work/${name}host.labels" "$work/${name}cortex_m4.labels"; then
        echo "$what: the firmware's labels differ from the host build's:"
        diff "$work/${name}host.labels" "$work/${name}cortex_m4.labels" | head -20
        exit 1
    fi
    grep -q '^end: ' "$work/${name}cortex_m4.labels" || { echo "$what: the firmware did not finish the stream"; exit 1; }
    echo "$what: labels: firmware and host agree on every line ($(grep -c '^settled ' "$work/${name}host.labels") settled label changes, $(grep '^end: ' "$work/${name}host.labels"))"
    # No heap: none of these may be linked in.
    heap=$(arm-none-eabi-nm "$elf" | grep -E ' (malloc|_malloc_r|free|_sbrk|_sbrk_r|_Znwj|_Znaj|_Znwm|_Znam|__cxa_allocate_exception)$' || true)
    if [ -n "$heap" ]; then
        echo "$what: the firmware links heap functions:"
        echo "$heap"
        exit 1
    fi
    echo "$what: heap: no malloc, _sbrk, operator new or __cxa_allocate_exception in the ELF"
}

# report ELF OUT: memory, flash by part and instructions per frame, as Markdown.
report() {
    elf=$1 out=$2
    arm-none-eabi-size -A "$elf" | awk '
        $1 == ".text" || $1 == ".ARM.exidx" { flash += $2 }
        $1 == ".data" { flash += $2; ram += $2 }
        $1 == ".bss" { ram += $2 }
        $1 == ".stack" { stack = $2 }
        END {
            printf "| memory | bytes | budget |\n|---|---:|---:|\n"
            printf "| flash (runtime + model + start-up) | %d | 131072 |\n", flash
            printf "| RAM (.data + .bss) | %d | |\n", ram
            printf "| RAM incl. reserved stack | %d | 16384 |\n", ram + stack
        }'
    grep '^# stack' "$out" | sed 's/^# /\n/'
    grep '^# state bytes' "$out" | sed 's/^# /\n/'
    echo
    echo "| flash by part | bytes |"
    echo "|---|---:|"
    arm-none-eabi-nm -S --size-sort -C -t d "$elf" | awk '
        NF >= 4 && $2 ~ /^[0-9]+$/ {
            size = $2 + 0; name = $0; sub(/^[^ ]+ [^ ]+ [^ ]+ /, "", name)
            if ($3 ~ /[bBdD]/ || seen[$1]++) next  # RAM, or an alias of a counted address
            if (name ~ /^actionstring_stream::/) next
            if (name ~ /kProjection/) part = "model: pose normalisation + PCA tables"
            else if (name ~ /kGmm/) part = "model: GMM tables"
            else if (name ~ /kNode|kCharacterDistances|kCharacterVotes/) part = "model: cluster tree, character distances W and votes"
            else if (name ~ /kExemplar/) part = "model: exemplars (clip classification)"
            else if (name ~ /kJointParents|kBoneLengths|kBoneOrder/) part = "model: skeleton (parents, bone lengths)"
            else if (name ~ /kRepresentative|kLabelNames|kJointNames|kPoseJoints|kModel/) part = "model: strings, labels, joints"
            else if (name ~ /normalize_pose|project_pose/) part = "code: normalise + project"
            else if (name ~ /gmm/) part = "code: GMM posterior (and init-time checks)"
            else if (name ~ /descend_tree|node_distance|StringEncoder/) part = "code: tree descent + string encoder"
            else if (name ~ /WindowMatcher|classify|ActionSegmenter/) part = "code: matcher, segmenter + classification"
            else if (name ~ /Annotator|validate_model|actionstring::/) part = "code: annotator + model validation"
            else if (name ~ /^__aeabi|^__.*(df|di|sf|si)[0-9]|^__udivmod|^__divmod|^mem/) part = "code: libgcc / libc helpers"
            else part = "code: replay harness + start-up"
            sum[part] += size
        }
        END { for (p in sum) printf "| %s | %d |\n", p, sum[p] }' | sort
    echo
    awk -v cal="$(sed -n 's/^# calibration instructions \([0-9]*\) cycles \([0-9]*\)$/\1 \2/p' "$out")" '
        BEGIN { split(cal, c, " "); per_cycle = c[1] / c[2] }
        /^# cycles / && $3 > 0 { n++; v[n] = $4 * per_cycle; if ($5 > 0) { t++; tv[t] = $4 * per_cycle } }
        /^# spread cycles / && $4 > 0 { sn++; sv[sn] = $5 * per_cycle; if ($6 > 0) { st++; stv[st] = $5 * per_cycle } }
        function sort_values(a, count,   i, j, x) { for (i = 2; i <= count; i++) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x } }
        function q(a, count, p,   k) { k = int(p * count); if (k < 1) k = 1; if (k > count) k = count; return a[k] }
        END {
            sort_values(v, n); sort_values(tv, t); sort_values(sv, sn); sort_values(stv, st)
            printf "Instructions per frame under QEMU (-icount shift=0, %.0f instructions per SysTick count, measured),\n", per_cycle
            printf "frames after the first:\n\n| frames | n | median | p99 | max |\n|---|---:|---:|---:|---:|\n"
            printf "| all | %d | %.0f | %.0f | %.0f |\n", n, q(v, n, 0.5), q(v, n, 0.99), v[n]
            printf "| frames that emit a character | %d | %.0f | %.0f | %.0f |\n", t, q(tv, t, 0.5), q(tv, t, 0.99), tv[t]
            printf "| all, work spread (spread_work) | %d | %.0f | %.0f | %.0f |\n", sn, q(sv, sn, 0.5), q(sv, sn, 0.99), sv[sn]
            printf "| frames that emit a character, work spread | %d | %.0f | %.0f | %.0f |\n", st, q(stv, st, 0.5), q(stv, st, 0.99), stv[st]
        }' "$out"
}

replay "" "committed model"

if [ -n "$c_api_test" ]; then
    stream_table --text --out "$work/stream.txt" 2>/dev/null
    # The C API runs both rules; its segmenter must settle exactly what the firmware's did.
    "$c_api_test" "$work/stream.txt" >"$work/c_api.settled"
    grep '^settled ' "$work/host.labels" >"$work/host.settled"
    if ! cmp -s "$work/host.settled" "$work/c_api.settled"; then
        echo "the C API's settled labels differ from the C++ build's:"
        diff "$work/host.settled" "$work/c_api.settled" | head -20
        exit 1
    fi
    echo "C API: the same $(wc -l <"$work/c_api.settled") settled label changes as the C++ build"
fi

# The paper's GMM model, trained from the data (its header is not committed).
"$cli" train --clips "$data/hdm05/train.tsv" --config "$source/models/hdm05-gmm.config" --out "$work/gmm.model" \
    >"$work/gmm.train.log" 2>&1 || { cat "$work/gmm.train.log"; exit 1; }
"$cli" codegen "$work/gmm.model" --out "$work/gmm_model.hpp.new" --namespace actionstring_hdm05_gmm >/dev/null
cmp -s "$work/gmm_model.hpp.new" "$work/gmm_model.hpp" 2>/dev/null || mv "$work/gmm_model.hpp.new" "$work/gmm_model.hpp"
rm -f "$work/gmm_model.hpp.new"
replay gmm_ "GMM model" -DACTIONSTRING_REPLAY_MODEL="$work/gmm_model.hpp" -DACTIONSTRING_REPLAY_MODEL_NAMESPACE=actionstring_hdm05_gmm

report=$work/firmware_report.md
{
    echo "## Cortex-M4F firmware (QEMU mps2-an386, $(arm-none-eabi-gcc -dumpversion), -Os)"
    echo
    echo "Stream: $(sed -n 's|^// DO NOT EDIT. Generated by `\(.*\)`.|\1|p' "$work/stream.hpp")"
    echo
    echo "### The committed model (models/hdm05_model.hpp)"
    echo
    report "$work/cortex_m4/actionstring_replay.elf" "$work/cortex_m4.out"
    echo
    echo "### The paper's GMM model (models/hdm05-gmm.config, trained by this test)"
    echo
    report "$work/gmm_cortex_m4/actionstring_replay.elf" "$work/gmm_cortex_m4.out"
} >"$report"
cat "$report"
