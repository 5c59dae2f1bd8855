#!/usr/bin/env bash
# The first command of the README: installs what is missing, builds in Release and runs the main
# job, `vt demo`, on the bundled default scene. Output goes to out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
# A unity build (8 sources of a target per translation unit), as scripts/test.sh configures the
# same folder: the build of `vt` alone is most of a first demo's time.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON \
  -DCMAKE_UNITY_BUILD_BATCH_SIZE=8
cmake --build build --parallel "$(nproc)" --target vt
./build/src/vt demo --output out/demo "$@"
