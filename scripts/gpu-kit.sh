#!/usr/bin/env bash
# Builds the GPU kit: what a bare x86-64 Linux machine with an OpenGL driver needs to draw
# everything `vt` judges (vt-capture, the libraries it links that such a machine lacks, libglvnd's
# EGL and GL loaders as Debian packages, the probe requests of `vt calibrate`, the demo's texture,
# q3dm6ish's retextured geometry and tour, the texture's layout as BC1 pages and as BC3 pages with
# noise as alpha, the hostile scene of scripts/stress-scene.py) and gpu-run.sh, the one command to
# run there.
#   scripts/gpu-kit.sh [--no-map] [--no-loaders] [--texture FILE] [--layout LAYOUT] [KIT]
#                                                                   (default KIT: .gpu-kit)
# --no-map leaves out q3dm6ish (no OpenArena fetch); --no-loaders the Debian packages (for a run on
# a machine that has its own, as the tests do); --texture the .vt drawn (default: the demo's,
# out/demo/scene.vt, made by `vt demo` if missing); --layout the layout it was built from, for the
# block-compressed textures (default: the demo's, with the demo's texture; else none). Then, on
# the GPU machine: bash KIT/gpu-run.sh OUT; back here: scripts/gpu-judge.sh OUT KIT.
set -euo pipefail
cd "$(dirname "$0")/.."

map=1 loaders=1 texture= layout=
usage="usage: scripts/gpu-kit.sh [--no-map] [--no-loaders] [--texture FILE] [--layout LAYOUT] [KIT]"
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --no-map) map=0 ;;
    --no-loaders) loaders=0 ;;
    --texture)
      [[ $# -ge 2 ]] || { echo "$usage" >&2; exit 2; }
      texture=$2
      shift
      ;;
    --layout)
      [[ $# -ge 2 ]] || { echo "$usage" >&2; exit 2; }
      layout=$2
      shift
      ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
  shift
done
kit=${1:-.gpu-kit}
build=${VT_BUILD_DIR:-build}
export LP_NUM_THREADS=${LP_NUM_THREADS:-2} EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}

[[ -f $build/build.ninja || -f $build/Makefile ]] ||
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" --target vt vt-capture
vt=$build/src/vt

work=$(mktemp -d "${TMPDIR:-/tmp}/vt-gpu-kit.XXXXXX")
trap 'rm -rf "$work"' EXIT
staging=$work/kit
mkdir -p "$staging/lib" "$staging/data" "$staging/probes"
cp "$build/src/vt-capture" "$staging/"
cp scripts/gpu-run.sh "$staging/"

# The shared libraries vt-capture links, but for the C library's own.
ldd "$build/src/vt-capture" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' |
  while read -r name path; do
    case $name in
      libc.so* | libm.so* | libdl.so* | libpthread.so* | librt.so* | ld-linux*) ;;
      *) cp -L "$path" "$staging/lib/$name" ;;
    esac
  done

# libglvnd: the EGL and OpenGL loaders that dispatch to the NVIDIA driver (its vendor library
# comes with the driver).
if ((loaders)); then
  mkdir -p "$staging/debs"
  chmod 755 "$work" "$staging"
  chmod 777 "$staging/debs"  # apt-get downloads as its own user
  (cd "$staging/debs" && apt-get download -q libegl1 libglvnd0 libopengl0 libgl1 libglx0 >&2)
fi

# The calibration's probe requests, recorded on this machine; their results are drawn there.
"$vt" calibrate --record-probes "$work/probes" -o "$work/here.json" >/dev/null
for file in "$work"/probes/*; do
  case $file in *.result | *.delta | */probes.json) ;; *) cp "$file" "$staging/probes/" ;; esac
done

# The texture of the named scenes and the map's flythrough: the demo's unless one is given.
if [[ -z $texture ]]; then
  [[ -f out/demo/scene.vt ]] || "$vt" demo --output out/demo >/dev/null
  texture=out/demo/scene.vt
  layout=${layout:-out/demo/scene/layout.json}
fi
cp "$texture" "$staging/data/scene.vt"
# The layout again as block-compressed pages: BC1, and BC3 with uniform noise as every image's
# alpha, so that every alpha palette mode shows in the frames (oiiotool: openimageio-tools).
if [[ -n $layout ]]; then
  "$vt" build "$layout" --format bc1 -o "$staging/data/scene_bc1.vt" >/dev/null
  noisy=$work/noisy-alpha
  mkdir -p "$noisy"
  python3 scripts/gpu-kit-noisy-layout.py "$layout" "$noisy" >"$noisy/images"
  while IFS=$'\t' read -r source target; do
    size=$(oiiotool --info "$source" | grep -o "[0-9]* x *[0-9]*" | head -1 | tr -d ' ')
    oiiotool "$source" --ch R,G,B --pattern noise:type=uniform:min=0:max=1 "$size" 1 --chappend \
      -o "$target"
  done <"$noisy/images"
  "$vt" build "$noisy/layout.json" --format bc3 -o "$staging/data/scene_bc3a.vt" >/dev/null
fi
# The hostile scene (huge, tiny and sliver triangles, vertices behind the camera), generated.
python3 scripts/stress-scene.py "$staging/data" >/dev/null
if ((map)); then
  packages=$(bash scripts/fetch-openarena.sh)
  "$vt" retexture q3dm6ish --packages "$packages" -o "$work/q3" --no-coherence >/dev/null
  cp "$work/q3/q3dm6ish.obj" "$work/q3/q3dm6ish.path.json" "$staging/data/"
fi

bytes=$(du -sb "$staging" | cut -f1)
if ((bytes > 48 * 1024 * 1024)); then
  echo "gpu-kit: $bytes bytes, more than 48 MiB" >&2
  exit 1
fi
rm -rf "$kit"
mv "$staging" "$kit"
echo "gpu-kit: wrote $kit ($((bytes / 1024)) KiB): run bash $kit/gpu-run.sh OUT on the GPU machine"
