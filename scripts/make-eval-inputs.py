#!/usr/bin/env python3
"""Writes the shipped scenes' data files into eval/scenes/:
- vessel.obj: a closed capsule (a vessel segment) along x, radius 0.35 m, 2.4 m from cap to cap;
- blade.obj: a convex blade 0.6 m long and 0.3 m tall, 10 mm thick at its back tapering to 2 mm
  at its edge;
- needle_hand.csv: a needle's insertion as a hand would record it: down at 0.5 m/s with a
  1 mm, 8 Hz tremor across the motion, then held.
Run from anywhere; the files are committed, this script says how they were made."""
import math
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "eval", "scenes")


def write_obj(path, header, vertices, faces):
    with open(path, "w") as f:
        f.write(f"# {header}\n# written by scripts/make-eval-inputs.py\n")
        for v in vertices:
            f.write("v %.6f %.6f %.6f\n" % v)
        for face in faces:
            f.write("f " + " ".join(str(i + 1) for i in face) + "\n")


def capsule(radius, half_length, around=24, cap_rings=6, body_rings=12):
    # Rings of `around` vertices from the -x pole to the +x pole; each cap a hemisphere.
    rings = []
    for k in range(1, cap_rings + 1):
        a = math.pi / 2 * (1 - k / cap_rings)  # from the pole towards the equator
        rings.append((-half_length - radius * math.sin(a), radius * math.cos(a)))
    for k in range(1, body_rings):
        rings.append((-half_length + 2 * half_length * k / body_rings, radius))
    for k in range(0, cap_rings):
        a = math.pi / 2 * k / cap_rings
        rings.append((half_length + radius * math.sin(a), radius * math.cos(a)))
    vertices = [(-half_length - radius, 0.0, 0.0)]
    for x, r in rings:
        for j in range(around):
            t = 2 * math.pi * j / around
            vertices.append((x, r * math.cos(t), r * math.sin(t)))
    vertices.append((half_length + radius, 0.0, 0.0))
    last = len(vertices) - 1
    faces = []
    # Counter-clockwise seen from outside.
    for j in range(around):
        faces.append((0, 1 + (j + 1) % around, 1 + j))
    for r in range(len(rings) - 1):
        a = 1 + r * around
        b = a + around
        for j in range(around):
            j1 = (j + 1) % around
            faces.append((a + j, a + j1, b + j1))
            faces.append((a + j, b + j1, b + j))
    a = 1 + (len(rings) - 1) * around
    for j in range(around):
        faces.append((a + j, a + (j + 1) % around, last))
    return vertices, faces


def blade():
    vertices = []
    for x in (-0.3, 0.3):
        for y, half in ((0.15, 0.005), (-0.15, 0.001)):
            for z in (-half, half):
                vertices.append((x, y, z))
    # Index: 4 * (x > 0) + 2 * (edge) + (z > 0); quads as two triangles, outward.
    quads = [(2, 3, 1, 0), (5, 7, 6, 4), (1, 5, 4, 0), (6, 7, 3, 2), (4, 6, 2, 0), (3, 7, 5, 1)]
    faces = []
    for q in quads:
        faces.append((q[0], q[1], q[2]))
        faces.append((q[0], q[2], q[3]))
    return vertices, faces


def needle_trajectory(path):
    with open(path, "w") as f:
        f.write("t,x,y,z\n")
        dt = 1 / 200
        for i in range(0, 401):
            t = i * dt
            y = 2.45 - 0.5 * min(t, 1.6)
            z = 0.001 * math.sin(2 * math.pi * 8 * t)
            f.write("%.4f,%.6f,%.6f,%.6f\n" % (t, 0.0, y, z))


if __name__ == "__main__":
    write_obj(os.path.join(OUT, "vessel.obj"), "a capsule along x: radius 0.35 m, 2.4 m long", *capsule(0.35, 0.85))
    write_obj(os.path.join(OUT, "blade.obj"), "a convex blade: 0.6 x 0.3 m, 10 mm back, 2 mm edge", *blade())
    needle_trajectory(os.path.join(OUT, "needle_hand.csv"))
