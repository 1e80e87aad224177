#!/bin/sh
# The evaluation study: error against run time for stock Bullet and ThinTool, from the same runs.
# Writes docs/study/*.csv (every run), docs/study.md (the tables) and docs/study-*.png (the plots,
# through gnuplot). Takes about a minute and a half on this project's 2-core machine; run it on a quiet
# machine, since the times are wall-clock. Needs the packages of scripts/install-deps.sh.
#
#   ./scripts/study.sh            the whole study
#   ./scripts/study.sh --quick    a few configurations, to check that it runs (seconds); writes
#                                 to build/study-quick, leaving docs/ as committed
set -eu
cd "$(dirname "$0")/.."
quick=${1:-}

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build --parallel 2 --target thintool_run
run="./build/eval/thintool_run --quiet"
out=docs/study
report=docs/study.md

algorithms=stock-A,stock-B,stock-E,ray-only,paper,swept
steps=1/30,1/60,1/240,1/1000
speeds=0.1,1,5,20,50
resolutions=63,255,1023,2047,8191,32767   # with exact_hull: 128, 512, 2,048, 4,096, 16,384, 65,536 faces
if [ "$quick" = "--quick" ]; then
  algorithms=stock-E,swept; steps=1/60; speeds=1,20; resolutions=63,255
  out=build/study-quick
  report=$out/study.md
fi
mkdir -p "$out"

# The needle's shipped trajectory is a recorded one; the matrix drives it at constant speeds.
needle_path='{"type":"constant_velocity","start":[0,2.083,0],"start_clearance":0.1,"direction":[0,-1,0],"distance":1.1}'

# 1. The matrix: the paper's 128-face ball; both tools, every algorithm, step and speed. The force
#    error is against swept detection at 1/1000 s on the 512-face ball at the same speed.
for scene in plate_press needle_press; do
  extra=""
  if [ "$scene" = needle_press ]; then extra="--set tools[0].trajectory=$needle_path"; fi
  # shellcheck disable=SC2086
  $run "eval/scenes/$scene.json" $extra --set thintool.force=true \
    --sweep "algorithm=$algorithms" --sweep "step.dt=$steps" --sweep "tools[0].trajectory.speed=$speeds" \
    --reference step.dt=1/1000 --reference algorithm=swept --reference soft.resolution=255 \
    --csv "$out/$scene-matrix.csv" > /dev/null
done

# 2. Cost against the soft body's size (the paper's Fig. 11): the plate at 1 m/s, 1/60 s, on
#    Bullet's ellipsoid of 128 to 65,536 faces, every point of its hull kept.
$run eval/scenes/plate_press.json --set thintool.force=true --set soft.exact_hull=true \
  --sweep "algorithm=$algorithms" --sweep "soft.resolution=$resolutions" \
  --csv "$out/plate_press-mesh.csv" > /dev/null

python3 scripts/study-report.py "$out" "$report"
echo "wrote $report and its plots"
