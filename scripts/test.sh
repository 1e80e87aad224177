#!/bin/sh
# Builds ThinTool with warnings as errors and runs the whole test suite (unit, integration,
# install and a brief benchmark run), then the same against Bullet's float64 build: the core
# computes in double either way, the glue converts. Needs the packages of scripts/install-deps.sh.
set -eu
cd "$(dirname "$0")/.."
cmake -S . -B build-float64 -DCMAKE_BUILD_TYPE=Release -DTHINTOOL_WERROR=ON -DTHINTOOL_BULLET_DOUBLE=ON \
  -DTHINTOOL_BUILD_BENCHMARKS=OFF
cmake --build build-float64 --parallel 2
ctest --test-dir build-float64 --parallel 2 --output-on-failure --exclude-regex 'Install|Docs'
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTHINTOOL_WERROR=ON
cmake --build build --parallel 2
ctest --test-dir build --parallel 2 --output-on-failure
