#!/bin/sh
# Regenerates the README's viewer screenshots under a virtual display (Xvfb, Mesa's software
# OpenGL). Needs a build in ./build with the viewer (see README) and xvfb-run.
set -eu
cd "$(dirname "$0")/.."
export LIBGL_ALWAYS_SOFTWARE=1
run() { xvfb-run -a -s "-screen 0 1280x720x24 -noreset" "$@"; }
run build/examples/plate_into_ball/plate_into_ball --screenshot docs/viewer-plate.png --after 60
run build/examples/plate_into_ball/plate_into_ball --tool needle --screenshot docs/viewer-needle.png --after 60
run build/examples/plate_into_ball/plate_into_ball --stock --screenshot docs/viewer-plate-stock.png --after 60
run build/examples/clamp_demo/clamp_demo --screenshot docs/viewer-clamp.png
run build/examples/clamp_demo/clamp_demo --vessel --screenshot docs/viewer-clamp-vessel.png
run build/examples/clamp_demo/clamp_demo --session --vessel --screenshot docs/viewer-clamp-session.png
run build/examples/gripper_grasp/gripper_grasp --screenshot docs/viewer-gripper.png
