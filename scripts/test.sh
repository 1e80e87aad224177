#!/bin/sh
# Runs the tests under AddressSanitizer and UndefinedBehaviorSanitizer against Bullet's float64
# build, and each libFuzzer target for a short, fixed run (both with clang); then builds ThinTool
# against Bullet's float build and runs the whole test suite (unit, integration, install and a brief
# benchmark run). Both Bullet builds are covered, with warnings as errors: the core computes in
# double either way, the glue converts. The generated scenes' verdicts (label "generated") are
# asserted in the float build only: which of those chaotic scenes fail depends on Bullet's
# precision (tests/eval/GeneratedScenesTest.cpp). The float build's ctest summary is the last
# thing printed.
# Needs the packages of scripts/install-deps.sh.
set -eu
cd "$(dirname "$0")/.."

# -O1 and line tables only: the sanitizers' usual setting. Clang builds this stage in 142 s on 2
# cores where GCC took 254 s with the same flags, and its tests run as fast (108 s against 117 s);
# the float build below is GCC's, so each compiler's warnings stop the suite. ThinTool's internal
# checks (THINTOOL_ASSERTS) run in this stage.
CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DTHINTOOL_WERROR=ON -DTHINTOOL_BULLET_DOUBLE=ON \
  -DTHINTOOL_SANITIZE=address,undefined,float-cast-overflow -DTHINTOOL_ASSERTS=ON -DTHINTOOL_BUILD_BENCHMARKS=OFF
cmake --build build-sanitize --parallel 2
# The stress cases at 1/10,000 s step the same code ten times as often as at 1/1000 s: under the
# sanitizers they took 94 s of this stage's 232 s of tests, so they run in the float build only.
# So do the deformable grasps with Bullet's face contacts on the fingers (40 s each here, 5 s in
# the float build), whose time goes to Bullet's deformable solve; the grasps without them run in
# both.
ctest --test-dir build-sanitize --parallel 2 --output-on-failure \
  --exclude-regex 'Install|Docs|dt110000s|GripperGraspDeformable.TheFingers(ReportWhatTheSolvesContactsCarry|LiftTheHeldPartOfTheCable)' \
  --label-exclude generated

CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTHINTOOL_BUILD_FUZZERS=ON \
  -DTHINTOOL_BUILD_TESTS=OFF -DTHINTOOL_BUILD_EXAMPLES=OFF -DTHINTOOL_BUILD_BENCHMARKS=OFF
cmake --build build-fuzz --parallel 2 --target fuzz_json fuzz_tool_model fuzz_replay
# A fixed seed and run count: the same inputs every time, so a CI run never fails by luck. Each
# fuzzer uses one core: they run side by side, each with its own log, shown when it fails.
fuzzing=""
for run in json:150000 tool_model:40000 replay:400000; do
  target=${run%%:*}
  # The shipped corpus is the seed; new finds go to a scratch copy, never into the tree.
  rm -rf "build-fuzz/corpus-$target" && cp -r "fuzz/corpus/$target" "build-fuzz/corpus-$target"
  "./build-fuzz/fuzz/fuzz_$target" -seed=1 -runs="${run#*:}" -artifact_prefix="build-fuzz/$target-" \
    "build-fuzz/corpus-$target" > "build-fuzz/$target.log" 2>&1 &
  fuzzing="$fuzzing $target:$!"
done
for job in $fuzzing; do
  if wait "${job#*:}"; then
    tail -n 1 "build-fuzz/${job%%:*}.log"
  else
    cat "build-fuzz/${job%%:*}.log"
    echo "test.sh: fuzz_${job%%:*} failed" >&2
    exit 1
  fi
done

# The Falcon backend too, against the shared libnifalcon source when it is at hand.
nifalcon=$(./scripts/build-nifalcon.sh build)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTHINTOOL_WERROR=ON ${nifalcon:+"-DCMAKE_PREFIX_PATH=$nifalcon"}
cmake --build build --parallel 2
ctest --test-dir build --parallel 2 --output-on-failure
