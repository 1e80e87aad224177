#!/bin/sh
# Builds libnifalcon (the Novint Falcon's open driver, not packaged for Debian) from the source
# copy in ../shared/third_party, or in the folder named by THINTOOL_THIRD_PARTY, into
# BUILD_DIR/nifalcon, and prints the install prefix to hand to CMake as CMAKE_PREFIX_PATH. With no
# copy at hand it says so on stderr, prints nothing and succeeds: the Falcon backend is optional.
# Needs libusb-1.0-0-dev. Usage: scripts/build-nifalcon.sh BUILD_DIR
set -eu
cd "$(dirname "$0")/.."
build=${1:?usage: scripts/build-nifalcon.sh BUILD_DIR}
source_dir=${THINTOOL_THIRD_PARTY:-../shared/third_party}
archive=$(ls "$source_dir"/libnifalcon-*.tar.gz 2>/dev/null | head -n 1 || true)
if [ -z "$archive" ]; then
  echo "build-nifalcon.sh: no libnifalcon source in $source_dir; the Falcon backend is not built" >&2
  exit 0
fi
work=$(cd "$(dirname "$build")" && pwd)/$(basename "$build")/nifalcon
prefix=$work/prefix
if [ ! -f "$prefix/include/falcon/core/FalconDevice.h" ]; then
  rm -rf "$work" && mkdir -p "$work"
  tar -xzf "$archive" -C "$work"
  cmake -S "$work"/libnifalcon-* -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" >&2
  cmake --build "$work/build" --parallel 2 >&2
  cmake --install "$work/build" >&2
fi
echo "$prefix"
