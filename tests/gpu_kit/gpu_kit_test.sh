#!/usr/bin/env bash
# The GPU kit on llvmpipe, as it would run on a bare GPU machine: built by scripts/gpu-kit.sh
# (without the map and the loader packages, which this machine has), its vt-capture resolving its
# libraries from the kit alone (ldd: nothing outside it but the C library's own), run by
# gpu-run.sh in an emptied environment, judged by scripts/gpu-judge.sh: the model fitted from the
# kit's probes is the one `vt calibrate` measures here, and the captures (of its texture, of
# the BC1 and BC3 versions of the texture's layout and of the hostile scene, and the frames of
# the flights streaming into the GL cache) are bit for bit.
#   gpu_kit_test.sh SOURCE BUILD WORK
set -euo pipefail
source=$1 build=$2 work=$3
export LP_NUM_THREADS=2 EGL_PLATFORM=surfaceless
rm -rf "$work"
mkdir -p "$work"
vt=$build/src/vt

"$vt" demo --output "$work/demo" >/dev/null
VT_BUILD_DIR=$build bash "$source/scripts/gpu-kit.sh" --no-map --no-loaders \
  --texture "$work/demo/scene.vt" --layout "$work/demo/scene/layout.json" "$work/kit"

outside=$(LD_LIBRARY_PATH="$work/kit/lib" ldd "$work/kit/vt-capture" |
  awk '$2 == "=>" {print $1, $3}' | grep -v "^lib\(c\|m\|dl\|pthread\|rt\)\.so" |
  grep -v " $work/kit/lib/" || true)
if [[ -n $outside ]]; then
  echo "FAIL: vt-capture resolves libraries outside the kit: $outside"
  exit 1
fi

env -i PATH=/usr/bin:/bin HOME="$work" VT_KIT_SYSTEM_GL=1 LP_NUM_THREADS=2 \
  EGL_PLATFORM=surfaceless VT_KIT_TIMING_SIZES=160x100 VT_KIT_FLIGHT_SIZE=160x100 bash "$work/kit/gpu-run.sh" "$work/out"
ls "$work/out"
# Under the fitted model only: the rows checked below (the gl45 verdicts of captures are checked by
# CaptureCrosscheck and GpuEvidence).
VT_JUDGE_GL45=0 VT_BUILD_DIR=$build VT="$vt" \
  bash "$source/scripts/gpu-judge.sh" "$work/out" "$work/kit" | tee "$work/table.md"

"$vt" calibrate -o "$work/here.json" >/dev/null
cmp "$work/here.json" "$work/out/model.json"
for set in captures captures-bc1 captures-bc3a; do
  grep -q "^| $set | model | 1024000 | 1024000 | 0 | 0 | 0.0000 |" "$work/table.md" || {
    echo "FAIL: the kit's $set are not bit for bit under the model fitted from its probes"
    exit 1
  }
done
grep -q "^| stress | model | 1408000 | 1408000 | 0 | 0 | 0.0000 |" "$work/table.md" || {
  echo "FAIL: the kit's hostile scene is not bit for bit under the model fitted from its probes"
  exit 1
}
for set in flight-rgba8 flight-linear-async flight-bc1; do
  grep -Eq "^\| $set \| model \| ([0-9]+) \| \1 \| 0 \| 0 \| 0\.0000 \|" "$work/table.md" || {
    echo "FAIL: the kit's $set flight is not bit for bit under the model fitted from its probes"
    exit 1
  }
done
echo "gpu kit: model and captures as here"
