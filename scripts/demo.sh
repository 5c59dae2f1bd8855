#!/usr/bin/env bash
# The first command of the README: installs what is missing, builds in Release and runs the main
# job, `vt demo`, on the bundled default scene. Output goes to out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target vt
./build/src/vt demo --output out/demo "$@"
