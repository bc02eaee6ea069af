"""Writes a joint CSV stream of the toy skeleton (root, lhipjoint, rhipjoint,
lhand, rhand) as a live source would: a header, then one frame per line,
hands going up and down, with two malformed lines and one frame without a body
(every joint field empty, as trackers export it) on the way (none with --clean).
    toy_stream.py [SECONDS] [--clean]"""
import math
import sys

clean = "--clean" in sys.argv[1:]
numbers = [a for a in sys.argv[1:] if a != "--clean"]
seconds = float(numbers[0]) if numbers else 8.0
print("time_ms,root_x,root_y,root_z,lhipjoint_x,lhipjoint_y,lhipjoint_z,rhipjoint_x,rhipjoint_y,rhipjoint_z,"
      "lhand_x,lhand_y,lhand_z,rhand_x,rhand_y,rhand_z,user")
frames = int(seconds * 30)
for f in range(frames):
    t = f / 30.0
    up = 0.5 + 0.45 * math.sin(2 * math.pi * t / 2.4)
    row = [0, 0.9, 0, 0, 0.9, -0.1, 0, 0.9, 0.1, 0.05, 0.9 + up, -0.25, 0.05, 0.9 + up * 0.5, 0.25]
    print(f"{t * 1000:.1f}," + ",".join(f"{v:.4f}" for v in row) + ",7")
    if f == 40 and not clean:
        print("this is not a frame")
    if f == 80 and not clean:
        print("1.0,2.0")
    if f == 120 and not clean:
        print(f"{t * 1000 + 10:.1f}," + "," * 14 + ",7")
    sys.stdout.flush()
