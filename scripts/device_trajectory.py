"""A scripted device trajectory for ReplayDevice: key poses (time s, x, y, z in device metres),
eased between with a half cosine so that each segment starts and stops smoothly, printed as the
CSV rows "time,x,y,z,buttons" at a fixed rate. Used by falcon-trajectory.py and
clamp-trajectory.py."""

import math


def pose(keys, t):
    for (t0, *a), (t1, *b) in zip(keys, keys[1:]):
        if t0 <= t <= t1:
            s = (t - t0) / (t1 - t0)
            s = 0.5 - 0.5 * math.cos(math.pi * s)  # smooth start and stop
            return [p + (q - p) * s for p, q in zip(a, b)]
    return keys[-1][1:]


def write(keys, rate=200):
    print("time,x,y,z,buttons")
    for i in range(int(keys[-1][0] * rate) + 1):
        t = i / rate
        x, y, z = pose(keys, t)
        print(f"{t:.3f},{x:.6f},{y:.6f},{z:.6f},0")
