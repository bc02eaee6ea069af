"""Per-frame cost of streaming from Python against the C++ annotator alone.

Streams every clip of hdm05/val.tsv (11,993 frames at 120 Hz) through
actionstring.Annotator.push_frame, one call per frame, with the model trained on
hdm05/train.tsv with models/hdm05-accurate.config, and reports the median and
percentiles per call beside the C++ annotator's own per-frame time on the same
frames (Model.evaluate's frame_time_ns, timed inside C++).

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_frame_overhead.py [passes]
"""
import os
import pathlib
import statistics
import sys
import time

import numpy as np

import actionstring

ROOT = pathlib.Path(__file__).resolve().parents[1]
data = pathlib.Path(os.environ.get("ACTIONSTRING_DATA", ROOT.parent / "shared" / "data"))
passes = int(sys.argv[1]) if len(sys.argv) > 1 else 5
train = actionstring.read_clip_list(data / "hdm05" / "train.tsv")
test = actionstring.read_clip_list(data / "hdm05" / "val.tsv")
model = actionstring.train(train, config=ROOT / "models" / "hdm05-accurate.config")

frames = [(t, f) for clip in test for t, f in zip(clip.times, clip.positions)]
# One stream: clips back to back on one clock.
times, offset = [], 0.0
for clip in test:
    times += [offset + t - clip.times[0] for t in clip.times]
    offset = times[-1] + 1 / 120
positions = [np.ascontiguousarray(f) for _, f in frames]

per_call = []
for p in range(passes + 1):
    annotator = actionstring.Annotator(model)
    for t, f in zip(times, positions):
        start = time.perf_counter_ns()
        annotator.push_frame(t, f)
        elapsed = time.perf_counter_ns() - start
        if p > 0:
            per_call.append(elapsed)
per_call.sort()
cpp = model.evaluate(test)["frame_time_ns"]


def q(values, fraction):
    return values[min(len(values) - 1, int(fraction * len(values)))]


print(f"{len(positions)} frames x {passes} passes, Python 3 {sys.version.split()[0]}, numpy {np.__version__}")
print(f"Annotator.push_frame from Python: median {q(per_call, 0.5) / 1000:.2f} us, "
      f"p90 {q(per_call, 0.9) / 1000:.2f} us, p99 {q(per_call, 0.99) / 1000:.2f} us")
print(f"C++ annotator alone (same frames): median {cpp['median'] / 1000:.2f} us, p99 {cpp['p99'] / 1000:.2f} us")
print(f"overhead of the Python call: {(q(per_call, 0.5) - cpp['median']) / 1000:.2f} us per frame (medians)")
