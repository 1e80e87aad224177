#!/bin/sh
# Runs ThinTool on random scenes (eval/SceneGenerator.h): count seeds (default 300) from first
# (default 1), in two halves side by side, and prints each failing seed and both halves'
# summaries. Builds nothing: needs thintool_generated in ./build (see README), or in the build
# folder named by THINTOOL_BUILD. Extra arguments after the two numbers go to thintool_generated
# (--algorithm stock-E). Exit status 1 when any scene failed.
set -eu
cd "$(dirname "$0")/.."
count=${1:-300}
first=${2:-1}
[ $# -gt 0 ] && shift
[ $# -gt 0 ] && shift
binary=${THINTOOL_BUILD:-build}/eval/thintool_generated
if [ ! -x "$binary" ]; then
  echo "generated-scenes.sh: $binary not found; build it first (cmake --build build --target thintool_generated)" >&2
  exit 2
fi
half=$((count / 2))
last=$((first + count - 1))
middle=$((first + half - 1))
tmp=$(mktemp -d)
status=0
if [ "$half" -gt 0 ]; then
  "$binary" --seeds "$first..$middle" "$@" > "$tmp/first.txt" &
  firstJob=$!
fi
"$binary" --seeds "$((middle + 1))..$last" "$@" > "$tmp/second.txt" || status=1
if [ "$half" -gt 0 ]; then
  wait "$firstJob" || status=1
  cat "$tmp/first.txt"
fi
cat "$tmp/second.txt"
echo "seeds $first..$middle: $(tail -n 1 "$tmp/first.txt" 2>/dev/null || echo none)"
echo "seeds $((middle + 1))..$last: $(tail -n 1 "$tmp/second.txt")"
rm -r "$tmp"
exit $status
