#!/usr/bin/env bash
# Mesa's driver options as implementations the oracle was not written for
# (docs/precision-models.md): for each variant, `vt calibrate` (exit code, families pinned and bounded), then the
# named scenes crosschecked under `auto`, `gl45` and the calibrated model. One line per variant.
#   scripts/driver-variants.sh TEXTURE.vt [SIZE]      (default size 160x100; build/src/vt)
# A conformant variant should calibrate (exit 0) and pass under every model; a rule breaker
# should be refused by vt calibrate (exit 1) and fail under auto and gl45.
set -uo pipefail
cd "$(dirname "$0")/.."
texture=${1:?usage: scripts/driver-variants.sh TEXTURE.vt [SIZE]}
size=${2:-160x100}
[[ -f $texture ]] || { echo "$texture: no such file" >&2; exit 1; }
export LP_NUM_THREADS=${LP_NUM_THREADS:-2} EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
softpipe="GALLIUM_DRIVER=softpipe MESA_GL_VERSION_OVERRIDE=4.5 MESA_GLSL_VERSION_OVERRIDE=450"
gl45="MESA_GL_VERSION_OVERRIDE=4.5 MESA_GLSL_VERSION_OVERRIDE=450"
variants=(
  "llvmpipe|"
  "caps-nosse|GALLIUM_OVERRIDE_CPU_CAPS=nosse"
  "caps-sse2|GALLIUM_OVERRIDE_CPU_CAPS=sse2"
  "caps-sse3|GALLIUM_OVERRIDE_CPU_CAPS=sse3"
  "caps-ssse3|GALLIUM_OVERRIDE_CPU_CAPS=ssse3"
  "caps-sse4.1|GALLIUM_OVERRIDE_CPU_CAPS=sse4.1"
  "caps-avx|GALLIUM_OVERRIDE_CPU_CAPS=avx"
  "vector-width-128|LP_NATIVE_VECTOR_WIDTH=128"
  "no-aos-sampling|GALLIVM_PERF=no_aos_sampling"
  "sse2-no-aos-sampling|GALLIUM_OVERRIDE_CPU_CAPS=sse2 GALLIVM_PERF=no_aos_sampling"
  "brilinear|GALLIVM_PERF=brilinear"
  "rho-approx|GALLIVM_PERF=rho_approx"
  "no-quad-lod|GALLIVM_PERF=no_quad_lod"
  "nopt|GALLIVM_PERF=nopt"
  "no-mipmap|LP_PERF=no_mipmap"
  "no-mip-linear|LP_PERF=no_mip_linear"
  "no-tex|LP_PERF=no_tex"
  "no-blend|LP_PERF=no_blend"
  "no-rast-linear|LP_PERF=no_rast_linear"
  "no-alphatest|LP_PERF=no_alphatest"
  "no-shade|LP_PERF=no_shade"
  "threads-0|LP_NUM_THREADS=0"
  "threads-1|LP_NUM_THREADS=1"
  "draw-no-fse|DRAW_NO_FSE=1"
  "draw-no-llvm|DRAW_USE_LLVM=0 $gl45"
  "softpipe|$softpipe"
  "softpipe-draw-llvm|$softpipe DRAW_USE_LLVM=1"
  "softpipe-draw-no-llvm|$softpipe DRAW_USE_LLVM=0"
  "softpipe-draw-no-fse|$softpipe DRAW_NO_FSE=1"
  "rule-breaker-no-linear|LP_PERF=no_linear"
  "rule-breaker-no-depth|LP_PERF=no_depth"
  "rule-breaker-texmem|LP_PERF=texmem"
  "rule-breaker-no-rast|LP_NO_RAST=1"
)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for entry in "${variants[@]}"; do
  name=${entry%%|*}
  read -r -a assignments <<< "${entry#*|}"
  calibration=$(env "${assignments[@]}" ./build/src/vt calibrate -o "$work/$name.json" 2>/dev/null)
  rc=$?
  line="$name: calibrate exit $rc, $(grep -c '\[pinned\]' <<< "$calibration") pinned, $(grep -c \
    '\[bounded\]' <<< "$calibration") bounded"
  models=(auto gl45)
  [[ $rc == 0 ]] && models+=("$work/$name.json")
  for model in "${models[@]}"; do
    verdict=$(env "${assignments[@]}" ./build/src/vt crosscheck "$texture" --size "$size" \
      --model "$model" -o "$work/out" 2>&1 | sed -n 's/^crosscheck: //p')
    label=$model
    [[ $model == "$work/$name.json" ]] && label=calibrated
    line+=" | $label: ${verdict:-no verdict}"
  done
  echo "$line"
done
