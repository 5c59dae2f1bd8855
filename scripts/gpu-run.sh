#!/usr/bin/env bash
# The one command to run on the GPU machine, from the kit scripts/gpu-kit.sh made:
#   bash KIT/gpu-run.sh OUT
# Unpacks libglvnd's loaders (root; unless VT_KIT_SYSTEM_GL=1 says the machine has its own),
# selects the NVIDIA EGL vendor where its file is found, then draws the calibration's probes, the
# named scenes (of the kit's texture and, where the kit has them, of its BC1 and BC3 versions) and
# the q3dm6ish flythrough and every 10th frame of the hostile scene's (captures) and times them at
# 1280 x 720 and 1920 x 1080 (VT_KIT_TIMING_SIZES overrides the sizes); then flies q3dm6ish's tour
# (without the map, the hostile scene's path) with the runtime streaming pages into the GL cache,
# three ways: the texture's pages, its BC1 blocks, and GL_LINEAR with the needbuffer read back one
# frame late (`vt-capture flight`, every 48th frame a capture; VT_KIT_FLIGHT_SIZE, default
# 320x200).
# OUT receives at most 9 files: log.txt, probes.tar.gz, captures.tar.gz, compressed.tar.gz,
# q3dm6ish.tar.gz, stress.tar.gz, flight.tar.gz, timings.json, timings-q3dm6ish.json. A step that fails is logged
# and the others still run; the exit status is that of the first failure.
set -uo pipefail
kit=$(cd "$(dirname "$0")" && pwd)
out=${1:?usage: gpu-run.sh OUT}
mkdir -p "$out"
out=$(cd "$out" && pwd)
log=$out/log.txt
: >"$log"

if [[ ${VT_KIT_SYSTEM_GL:-0} != 1 && -d $kit/debs ]]; then
  for deb in "$kit"/debs/*.deb; do dpkg -x "$deb" /; done
  ldconfig
fi
export LD_LIBRARY_PATH="$kit/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
for vendor in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json \
  /usr/share/glvnd/egl_vendor.d/10_nvidia.json; do
  if [[ -f $vendor && -z ${__EGL_VENDOR_LIBRARY_FILENAMES:-} ]]; then
    export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
  fi
done

work=$(mktemp -d "${TMPDIR:-/tmp}/vt-gpu-run.XXXXXX")
trap 'rm -rf "$work"' EXIT
status=0
step() {  # name, command...
  local name=$1
  shift
  echo "== $name: $*" >>"$log"
  local start=$SECONDS
  if "$@" >>"$log" 2>&1; then
    echo "== $name: done in $((SECONDS - start)) s" >>"$log"
  else
    local code=$?
    echo "== $name: FAILED (exit $code)" >>"$log"
    ((status == 0)) && status=$code
  fi
}

{
  uname -a
  nvidia-smi --query-gpu=name,driver_version --format=csv 2>/dev/null || true
  echo "__EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-}"
  ldd "$kit/vt-capture"
} >>"$log" 2>&1

capture=$kit/vt-capture
texture=$kit/data/scene.vt
step probes "$capture" probes "$kit/probes" -o "$work/probes"
step captures "$capture" scenes "$texture" --texture-name scene.vt -o "$work/captures"
for variant in bc1 bc3a; do
  if [[ -f $kit/data/scene_$variant.vt ]]; then
    step "captures-$variant" "$capture" scenes "$kit/data/scene_$variant.vt" \
      --texture-name "scene_$variant.vt" -o "$work/compressed/captures-$variant"
  fi
done
sizes=${VT_KIT_TIMING_SIZES:-1280x720,1920x1080}
step timings "$capture" timings "$texture" --sizes "$sizes" -o "$out/timings.json"
if [[ -f $kit/data/q3dm6ish.obj ]]; then
  map=(--mesh "$kit/data/q3dm6ish.obj" --path "$kit/data/q3dm6ish.path.json" --every 96)
  step q3dm6ish "$capture" scenes "$texture" "${map[@]}" --texture-name scene.vt \
    -o "$work/q3dm6ish"
  step timings-q3dm6ish "$capture" timings "$texture" "${map[@]}" --sizes "$sizes" \
    -o "$out/timings-q3dm6ish.json"
fi
if [[ -f $kit/data/stress.obj ]]; then
  step stress "$capture" scenes "$texture" --mesh "$kit/data/stress.obj" \
    --path "$kit/data/stress.path.json" --every 10 --texture-name scene.vt -o "$work/stress"
fi
flown=()
if [[ -f $kit/data/q3dm6ish.obj ]]; then
  flown=(--mesh "$kit/data/q3dm6ish.obj" --path "$kit/data/q3dm6ish.path.json" --every 48)
elif [[ -f $kit/data/stress.obj ]]; then
  flown=(--mesh "$kit/data/stress.obj" --path "$kit/data/stress.path.json" --every 10)
fi
if ((${#flown[@]})); then
  flown+=(--size "${VT_KIT_FLIGHT_SIZE:-320x200}")
  step flight "$capture" flight "$texture" "${flown[@]}" --texture-name scene.vt \
    -o "$work/flight/rgba8"
  step flight-linear-async "$capture" flight "$texture" "${flown[@]}" --linear --async-readback \
    --heuristic 'pixelsum*distance' --texture-name scene.vt -o "$work/flight/linear-async"
  if [[ -f $kit/data/scene_bc1.vt ]]; then
    step flight-bc1 "$capture" flight "$kit/data/scene_bc1.vt" "${flown[@]}" \
      --texture-name scene_bc1.vt -o "$work/flight/bc1"
  fi
fi
for folder in probes captures compressed q3dm6ish stress flight; do
  [[ -d $work/$folder ]] && tar -C "$work" -czf "$out/$folder.tar.gz" "$folder"
done
echo "== status $status" >>"$log"
exit "$status"
