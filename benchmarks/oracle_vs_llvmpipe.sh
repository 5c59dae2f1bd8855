#!/usr/bin/env bash
# The oracle against llvmpipe on what users draw (build/benchmarks/oracle_vs_llvmpipe): the
# generated terrain, and tour frames of q3dm6ish and am_thornish where OpenArena can be fetched
# (scripts/fetch-openarena.sh; $VT_OPENARENA_DIR names the .pk3 folder instead), retextured and
# built once into $VT_DATA_CACHE/oracle-bench (default ~/.cache/vt/oracle-bench). Runs the
# benchmark three times and prints each row's range over the runs: llvmpipe and the oracle draw
# the same frames in the same process each time, so each run's ratios are comparable although
# the machine is noisy. Nothing else should run on the machine meanwhile.
#   usage: benchmarks/oracle_vs_llvmpipe.sh [--build DIR] [--runs N] [--frames N]
set -euo pipefail
cd "$(dirname "$0")/.."
usage='usage: benchmarks/oracle_vs_llvmpipe.sh [--build DIR] [--runs N] [--frames N]'
build=build
runs=3
frames=3
while (($#)); do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
done
vt=$(realpath "$build/src/vt")
bench=$(realpath "$build/benchmarks/oracle_vs_llvmpipe")
work=${VT_DATA_CACHE:-$HOME/.cache/vt}/oracle-bench
mkdir -p "$work"

maps=()
if baseoa=${VT_OPENARENA_DIR:-$(bash scripts/fetch-openarena.sh 2>/dev/null)}; then
  for map in q3dm6ish am_thornish; do
    if [[ ! -f "$work/$map.vt" ]]; then
      "$vt" retexture "$map" --packages "$baseoa" -o "$work/$map" --no-coherence > /dev/null
      "$vt" build "$work/$map/$map.layout.json" -o "$work/$map.vt" -q
    fi
    maps+=(--map "$map" "$work/$map.vt" "$work/$map/$map.obj" "data/paths/$map.storyboard.json")
  done
else
  echo "OpenArena unavailable: the generated terrain only" >&2
fi

export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
for ((run = 1; run <= runs; ++run)); do
  "$bench" --frames "$frames" "${maps[@]}" | tee "$work/run$run.txt"
done
python3 - "$work" "$runs" <<'PY'
import sys
work, runs = sys.argv[1], int(sys.argv[2])
rows = {}
for run in range(1, runs + 1):
    lines = open(f"{work}/run{run}.txt").read().splitlines()
    header = lines[1].split()
    for line in lines[2:]:
        cells = line.split()
        if len(cells) != len(header) or not cells[2].isdigit():
            continue
        rows.setdefault((cells[0], cells[1]), []).append(dict(zip(header, cells)))
print(f"\nover {runs} runs (min - max):")
print(f"{'scene':12} {'size':9} {'ratio':>13} {'scaling':>13} {'gl45/pin':>15} {'sets%':>13} "
      f"{'all/pin':>15}")
for (scene, size), values in rows.items():
    def span(key):
        v = sorted(float(r[key].rstrip('x%')) for r in values)
        return f"{v[0]:.2f} - {v[-1]:.2f}"
    print(f"{scene:12} {size:9} {span('ratio'):>13} {span('scaling'):>13} {span('gl45/pin'):>15} "
          f"{span('sets%'):>13} {span('all/pin'):>15}")
PY
