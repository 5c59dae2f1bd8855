#!/usr/bin/env bash
# Installs with apt-get the Debian 12 packages this project needs and that are
# missing; with --demo only those the `vt` executable needs. Idempotent: when everything is
# present it only asks dpkg and exits.
set -euo pipefail

# What `vt` needs to build and run (scripts/demo.sh installs only these: --demo).
demo_packages=(
  # toolchain
  g++ cmake ninja-build pkg-config
  # geometry, images, ray tracing, meshes; Debian 12's OpenImageIO CMake package names the
  # command-line tools as imported targets and fails without them (openimageio-tools)
  libglm-dev libopenimageio-dev openimageio-tools libembree-dev libtinyobjloader-dev
  # Quake 3 maps: .pk3 archives are zip files
  libzip-dev
  # block-compressed pages (BC1, BC3)
  libsquish-dev
  # headless OpenGL through EGL (Mesa llvmpipe) with libepoxy
  libegl-dev libegl1-mesa-dev libgl1-mesa-dri libopengl-dev libgl-dev libepoxy-dev
  # the interactive viewer (GLFW)
  libglfw3-dev
  # command line, JSON, checksums, parallel loops
  libcli11-dev nlohmann-json3-dev libxxhash-dev libtbb-dev
)
# What the tests, the fuzzers, the benchmarks and the report scripts need besides.
test_packages=(
  clang-format
  # fuzzing (scripts/fuzz.sh): clang with libFuzzer's runtime, llvm-symbolizer for the reports
  clang libclang-rt-14-dev llvm
  # the interactive viewer, tested under a virtual X server
  xvfb xauth
  # report scripts and the plots of `vt eval` (matplotlib, with numpy), and scikit-image: the
  # independent SSIM the metrics are checked against
  python3 python3-matplotlib python3-numpy python3-skimage
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # the frame-by-frame inspect page is tested in headless Chromium
  chromium
  # measurement for the benchmarks: GNU time
  time
)
packages=("${demo_packages[@]}")
case "${1:-}" in
  --demo) ;;
  "") packages+=("${test_packages[@]}") ;;
  *) echo "usage: scripts/install-deps.sh [--demo]" >&2; exit 2 ;;
esac

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null || true)
  [[ "$status" == "installed" ]] || missing+=("$package")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=()
if ((EUID != 0)); then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
