#!/usr/bin/env bash
# How the chapter-4 reproduction's cache size was chosen: PixelSum at 5 and at 10 pages per frame
# on both indoor maps (the thesis's layout, their storyboards, 1024 x 768) with caches of 16^2 to
# 48^2 frames (data/chapter4/cache-sweep.json), and for each cache the regime check of
# scripts/chapter4-report.py: PixelSum 10 - PixelSum 5 on mean SSIM, its 95% block-bootstrap
# interval, whether the lower bound exceeds the half-width, and the fraction of resamples at or
# below zero, and the pages each of the two evicted. The reproduction's per-map caches
# (scripts/reproduce-chapter4.sh) were chosen from its output. About 5 minutes on the project's
# 2-core machine once the textures are built.
#   usage: scripts/chapter4-cache-sweep.sh [--vt path/to/vt]
# The textures are those of scripts/reproduce-chapter4.sh in $VT_DATA_CACHE/chapter4 (run it, or
# its --maps part, first); the `vt eval` folders go to $VT_DATA_CACHE/chapter4/cache-sweep.
set -euo pipefail
cd "$(dirname "$0")/.."
usage='usage: scripts/chapter4-cache-sweep.sh [--vt path/to/vt]'
vt=build/src/vt
while (($#)); do
  case "$1" in
    --vt) vt=$2; shift 2 ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
done
work=${VT_DATA_CACHE:-${HOME:-/tmp}/.cache/vt}/chapter4
for map in q3dm6ish am_thornish; do
  [[ -f "$work/$map.baseline.vt" ]] ||
    { echo "$work/$map.baseline.vt: not built; run scripts/reproduce-chapter4.sh first" >&2; exit 1; }
done
python=/usr/bin/python3
[[ -x "$python" ]] || python=python3
for map in q3dm6ish am_thornish; do
  "$vt" eval "$work/$map.baseline.vt" --mesh "$work/$map.baseline/$map.obj" \
    --path "data/paths/$map.storyboard.json" --configs data/chapter4/cache-sweep.json \
    --title "$map, cache sweep" --size 1024x768 -o "$work/cache-sweep/$map" > /dev/null
done
"$python" - "$work/cache-sweep" <<'PY'
import csv, importlib.util, json, os, sys
import numpy as np
spec = importlib.util.spec_from_file_location("report", "scripts/chapter4-report.py")
report = importlib.util.module_from_spec(spec)
spec.loader.exec_module(report)
for map in ("q3dm6ish", "am_thornish"):
    folder = os.path.join(sys.argv[1], map)
    summary = json.load(open(os.path.join(folder, "summary.json")))
    ssim = {}
    for row in csv.DictReader(open(os.path.join(folder, "frames.csv"))):
        ssim.setdefault(int(row["configuration"]), []).append(float(row["ssim"]))
    blocks, _ = report.blocks_of(report.segments_of(summary), list(range(summary["frames"])))
    names = [run["name"] for run in summary["runs"]]
    for five in range(0, len(names), 2):
        difference = np.array(ssim[five + 1]) - np.array(ssim[five])
        mean, (low, high) = report.block_bootstrap(difference, blocks)
        sums = np.array([difference[b].sum() for b in blocks])
        counts = np.array([len(b) for b in blocks], dtype=float)
        rng = np.random.default_rng(report.BOOTSTRAP_SEED)
        draws = rng.integers(0, len(blocks), size=(report.RESAMPLES, len(blocks)))
        at_most_zero = np.mean(sums[draws].sum(axis=1) / counts[draws].sum(axis=1) <= 0)
        half = (high - low) / 2
        print(f"{map:12s} {names[five + 1]} - {names[five]}: {mean:+.2e} "
              f"[{low:+.2e}, {high:+.2e}], half-width {half:.2e}, wide margin "
              f"{'yes' if low > half else 'no'}, resamples <= 0: {at_most_zero:.4f}, "
              f"evicted {summary['runs'][five]['evicted']} and {summary['runs'][five + 1]['evicted']}")
PY
