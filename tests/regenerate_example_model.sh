#!/bin/sh
# Retrains the committed example model from the data and checks that the
# generated header is byte-for-byte the committed one.
#   regenerate_example_model.sh CLI SOURCE_DIR WORK_DIR
# Exits 77 (CTest: skipped) when the HDM05 data is absent.
set -eu
cli=$1 source=$2 work=$3
data=${ACTIONSTRING_DATA:-$source/../shared/data}
if [ ! -f "$data/hdm05/train.tsv" ]; then
    echo "SKIPPED: $data/hdm05/train.tsv not found (set ACTIONSTRING_DATA)"
    exit 77
fi
mkdir -p "$work"
"$cli" train --clips "$data/hdm05/train.tsv" --config "$source/models/hdm05.config" --out "$work/hdm05.model" > "$work/train.log" 2>&1
"$cli" codegen "$work/hdm05.model" --out "$work/hdm05_model.hpp" --namespace actionstring_hdm05
if ! cmp -s "$work/hdm05_model.hpp" "$source/models/hdm05_model.hpp"; then
    echo "models/hdm05_model.hpp differs from a fresh regeneration ($work/hdm05_model.hpp):"
    diff "$source/models/hdm05_model.hpp" "$work/hdm05_model.hpp" | head -20
    exit 1
fi
echo "models/hdm05_model.hpp regenerates byte for byte"
