#!/usr/bin/env python3
# Writes the clamp session's scripted device trajectory (device metres, 200 Hz) for one body:
#   python3 scripts/clamp-trajectory.py sphere > examples/clamp_demo/grasp-sphere.csv
#   python3 scripts/clamp-trajectory.py vessel > examples/clamp_demo/grasp-vessel.csv
# The phases of clamp_demo's scripted run: close 1.5 s (pushing the grip away closes the clamp),
# settle 0.5 s, lift 1 s, hold 2 s, open 0.5 s, let the body fall 1.5 s. The session maps the
# device's centre to the open clamp at its hinge, 20 world metres per device metre in the plane
# (the lift: 5 cm at the grip, 1 m in the world), 30 rad per device metre of push.

import math

import device_trajectory
import sys

HINGE_DISTANCE = 2.3     # m, world, from the body's centre (scenes/ClampScene.cpp)
SQUEEZE = 0.2            # of the body's width across the jaws
RADIUS = {"sphere": 1.0, "vessel": 0.35}
MAX_OPENING = math.pi / 2
RADIANS_PER_METRE = 30
LIFT = 1.0 / 20          # device metres for 1 m in the world

body = sys.argv[1] if len(sys.argv) > 1 else ""
if body not in RADIUS:
    sys.exit("usage: clamp-trajectory.py sphere|vessel")
closed = 2 * math.atan((1 - SQUEEZE) * RADIUS[body] / HINGE_DISTANCE)
push = (closed - MAX_OPENING) / RADIANS_PER_METRE  # negative: away from the user

# (time s, x, y, z) key poses; positions are eased between them.
KEYS = [
    (0.0, 0.0, 0.0, 0.0),
    (1.5, 0.0, 0.0, push),   # close
    (2.0, 0.0, 0.0, push),   # settle
    (3.0, 0.0, LIFT, push),  # lift
    (5.0, 0.0, LIFT, push),  # hold
    (5.5, 0.0, LIFT, 0.0),   # open
    (7.0, 0.0, LIFT, 0.0),   # the body falls
]


device_trajectory.write(KEYS)
