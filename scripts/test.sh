#!/bin/sh
# Builds ThinTool with warnings as errors and runs the whole test suite (unit, integration,
# install and a brief benchmark run). Needs the packages of scripts/install-deps.sh.
set -eu
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTHINTOOL_WERROR=ON
cmake --build build --parallel 2
ctest --test-dir build --parallel 2 --output-on-failure
