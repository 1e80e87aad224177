#!/bin/sh
# Installs the Debian bookworm packages that building, testing and benchmarking ThinTool need
# (RapidJSON reads the evaluation suite's scene files and tinyobjloader its OBJ meshes, python3
# writes its study's report);
# gnuplot-nox draws the examples' plots (optional: without it they write CSV only); clang and its
# runtime build the libFuzzer targets; GLFW, OpenGL, Dear ImGui and stb build the examples' viewer
# (optional), and Xvfb with Mesa's software OpenGL renders it headless for its tests; libusb-1.0
# builds libnifalcon for the Falcon backend (optional, scripts/build-nifalcon.sh).
set -eu
if [ "$(id -u)" -eq 0 ]; then run=""; else run="sudo"; fi
$run apt-get update -qq
$run env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
  cmake g++ make pkg-config libbullet-dev libgtest-dev libbenchmark-dev \
  libtinyobjloader-dev rapidjson-dev python3 gnuplot-nox clang libclang-rt-14-dev \
  libglfw3-dev libgl-dev libimgui-dev libstb-dev xvfb xauth libgl1-mesa-dri libusb-1.0-0-dev
