"""What a sensor's up direction buys: each clip of a list streamed as a sensor pitched
by DEG degrees (about its horizontal x axis) would see it, with and without the
annotator told the sensor's up (AnnotatorConfig::up), and each frame's settled label
compared with the label the upright clip gets.

    PYTHONPATH=build/release/python /usr/bin/python3 scripts/sensor_up.py MODEL LIST DEG

needs the Python extension built (-DACTIONSTRING_BUILD_PYTHON=ON) and a y-up list
(Kinect: MSR Action3D, UTKinect intervals). Prints one line: the share of frames
labelled as upright with the up given and without it.
"""
import sys

import numpy as np

import actionstring


def frame_labels(segments, times):
    """The settled label of each frame time: the segment holding it (None between)."""
    labels = []
    for t in times:
        label = None
        for segment in segments:
            if segment["start"] <= t <= segment["end"]:
                label = segment["label"]
        labels.append(label)
    return labels


def main(argv):
    if len(argv) != 4:
        sys.exit(__doc__)
    model = actionstring.Model.load(argv[1])
    clips = actionstring.read_clip_list(argv[2])
    angle = np.radians(float(argv[3]))
    c, s = np.cos(angle), np.sin(angle)
    pitch = np.array([[1, 0, 0], [0, c, -s], [0, s, c]], dtype=np.float32)
    same_with, same_without, frames = 0, 0, 0
    for clip in clips:
        if clip.up_axis != 1:
            sys.exit(f"{clip.source}: expected a y-up clip")
        positions = np.asarray(clip.positions)
        lost = np.abs(positions).sum(axis=(1, 2)) == 0  # lost tracking stays all zero
        seen = positions @ pitch.T
        seen[lost] = 0
        tilted = actionstring.Clip(np.ascontiguousarray(seen, dtype=np.float32), times=np.asarray(clip.times),
                                   joint_names=list(clip.joint_names), up_axis=clip.up_axis)
        up = tuple(float(v) for v in pitch[:, 1])  # the world's up as the pitched sensor sees it
        upright = frame_labels(model.annotate(clip), clip.times)
        given = frame_labels(model.annotate(tilted, up=up), clip.times)
        unturned = frame_labels(model.annotate(tilted), clip.times)
        same_with += sum(a == b for a, b in zip(given, upright))
        same_without += sum(a == b for a, b in zip(unturned, upright))
        frames += len(upright)
    print(f"pitched {float(argv[3]):g} degrees: frames labelled as upright with the up given "
          f"{same_with / frames:.4f}, without {same_without / frames:.4f} ({frames} frames, {len(clips)} clips)")


if __name__ == "__main__":
    main(sys.argv)
