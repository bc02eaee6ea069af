#!/bin/sh
# `pip install .` from the source tree into a fresh virtual environment (with
# the system's site packages: NumPy, pytest, setuptools from Debian), then
# imports the package and streams a frame: what a researcher does first.
#   pip_install_check.sh PYTHON SOURCE_DIR WORK_DIR
set -eu
python=$1 source=$2 work=$3
rm -rf "$work"
"$python" -m venv --system-site-packages "$work/venv"
# A copy of the tree without build folders, as a fresh clone has it.
mkdir -p "$work/src"
tar -C "$source" --exclude=./build --exclude=./.git -cf - . | tar -C "$work/src" -xf -
cd "$work/src"
CMAKE_BUILD_PARALLEL_LEVEL=2 "$work/venv/bin/pip" install --no-build-isolation --no-deps --no-index -q . \
    >"$work/pip.log" 2>&1 || { tail -30 "$work/pip.log"; exit 1; }
cd "$work"
"$work/venv/bin/python" - <<'PY'
import numpy as np
import actionstring
print("imported actionstring", actionstring.__version__, "from", actionstring.__file__)
clips = actionstring._native._toy_clips(2, 3)
model = actionstring.train(clips, components=0, pca=8, string_rate=10, sigma=4.0)
annotator = actionstring.Annotator(model)
print(annotator.push_frame(0.0, clips[0].positions[0]))
PY
