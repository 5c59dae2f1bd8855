#!/usr/bin/env bash
# The first command of the README: installs what is missing, builds in Release and runs the main
# job, `vt demo`, on the bundled default scene. Output goes to out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."

# Only the packages `vt` needs, and a unity build (8 sources of a target per translation unit) of
# `vt` alone without the tests and benchmarks (scripts/test.sh configures the same folder with
# them): on a fresh machine the packages and this build are most of a first demo's time. The
# compiler flags are scripts/test.sh's (warnings as errors among them), so that the test command
# after the demo compiles only what the demo did not.
bash scripts/install-deps.sh --demo
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON \
  -DCMAKE_UNITY_BUILD_BATCH_SIZE=8 -DVT_WARNINGS_AS_ERRORS=ON -DVT_BUILD_TESTS=OFF \
  -DVT_BUILD_BENCHMARKS=OFF
cmake --build build --parallel "$(nproc)" --target vt
./build/src/vt demo --output out/demo "$@"
