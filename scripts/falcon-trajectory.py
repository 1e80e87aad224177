#!/usr/bin/env python3
# Writes the Falcon demo's scripted trajectory (device metres, 200 Hz):
#   python3 scripts/falcon-trajectory.py > examples/falcon_demo/press.csv
# Hold, a slow press, a slide while pressed, a fast withdrawal, a quick second press, release.
# Device y is up; the device's origin sits 15 cm (world) above the ball, 10 world cm per device cm.

import device_trajectory

# (time s, x, y, z) key poses; positions are eased between them.
KEYS = [
    (0.0, 0.0, 0.0, 0.0),
    (0.5, 0.0, 0.0, 0.0),
    (2.5, 0.0, -0.03, 0.0),     # slow press, 1.5 cm/s: 15 cm world below the top
    (3.0, 0.0, -0.03, 0.0),
    (4.0, 0.01, -0.03, 0.0),    # slide 10 cm world while pressed
    (4.1, 0.01, 0.01, 0.0),     # fast withdrawal, 40 cm/s
    (4.6, 0.01, 0.01, 0.0),
    (4.9, 0.0, -0.025, 0.0),    # quick second press
    (5.4, 0.0, -0.025, 0.0),
    (5.9, 0.0, 0.01, 0.0),      # release
    (6.2, 0.0, 0.01, 0.0),
]


device_trajectory.write(KEYS)
