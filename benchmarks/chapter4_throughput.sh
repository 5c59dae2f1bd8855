#!/usr/bin/env bash
# Where the chapter-4 reproduction's time goes (issue 19), on a real map at 1024 x 768:
#  1. one storyboard configuration flown by `vt fly --quality`, every frame drawn by the flight
#     itself: seconds per frame of drawing (colour + needbuffer), analysis, streaming, the
#     reference image and SSIM/WSSIM;
#  2. `vt eval` of a whole configuration file over the same frames, each view drawn once for every
#     configuration and shaded per cache state: the shared passes, the shading, and per
#     configuration-frame the analysis, streaming and metrics; and the ratio of the evaluation's
#     time per configuration-frame to the lone flight's (both measured here, in one script).
# Needs the q3dm6ish textures of the reproduction ($VT_DATA_CACHE/chapter4, made by
# scripts/reproduce-chapter4.sh or its --miniature).
#   usage: benchmarks/chapter4_throughput.sh [--frames N] [--size WxH] [--vt path/to/vt]
set -euo pipefail
cd "$(dirname "$0")/.."
frames=60
size=1024x768
vt=build/src/vt
while (($#)); do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --vt) vt=$2; shift 2 ;;
    *) echo "usage: benchmarks/chapter4_throughput.sh [--frames N] [--size WxH] [--vt path/to/vt]" >&2; exit 2 ;;
  esac
done
vt=$(realpath "$vt")
data=${VT_DATA_CACHE:-${HOME:-/tmp}/.cache/vt}/chapter4
texture=$data/q3dm6ish.baseline.vt
mesh=$data/q3dm6ish.baseline/q3dm6ish.obj
if [[ ! -f $texture || ! -f $mesh ]]; then
  echo "benchmarks/chapter4_throughput.sh: $texture is missing: run scripts/reproduce-chapter4.sh --miniature first" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The storyboard cut to the motions that start within its first `frames` frames, each whole (a
# motion cut short would keep its angle and turn faster than its kind allows).
python3 - data/paths/q3dm6ish.storyboard.json "$frames" "$work/path.json" <<'PY'
import json, sys
story = json.load(open(sys.argv[1]))
limit, kept, frames = int(sys.argv[2]), [], 0
for step in story["storyboard"]:
    if frames >= limit:
        break
    kept.append(step)
    frames += step["frames"]
json.dump({"start": story["start"], "storyboard": kept}, open(sys.argv[3], "w"))
PY

echo '{"heuristic": "pixelsum", "budget": 5, "cache_frames": 32, "initial_levels": 3,
  "preload_visible": true}' > "$work/pixelsum5.json"
/usr/bin/time -f "%e %M" -o "$work/fly.time" "$vt" fly "$texture" --mesh "$mesh" \
  --path "$work/path.json" --size "$size" --config "$work/pixelsum5.json" \
  --quality --threads 1 -o "$work/fly" > /dev/null
/usr/bin/time -f "%e %M" -o "$work/eval.time" "$vt" eval "$texture" --mesh "$mesh" \
  --path "$work/path.json" --size "$size" --configs data/chapter4/indoor.json --jobs "$(nproc)" \
  -o "$work/eval" > /dev/null

python3 - "$work" "$(nproc)" <<'PY'
import json, os, sys
work, cores = sys.argv[1], int(sys.argv[2])
fly = json.load(open(os.path.join(work, "fly", "timing.json")))
n = fly["frames"]
t = fly["times"]
print(f"vt fly --quality, one configuration, one thread, {n} frames (seconds per frame):")
for key in ("draw", "analysis", "streaming", "reference", "metrics"):
    print(f"  {key:<10} {t[key] / n:8.4f}")
alone = (t["draw"] + t["analysis"] + t["streaming"] + t["reference"] + t["metrics"]) / n
print(f"  {'total':<10} {alone:8.4f}")

s = json.load(open(os.path.join(work, "eval", "summary.json")))
runs = len(s["runs"])
sums = {k: sum(r["times"][k] for r in s["runs"]) for k in ("analysis", "streaming", "metrics")}
wall_eval, peak = open(os.path.join(work, "eval.time")).read().split()
print(f"vt eval of data/chapter4/indoor.json: {runs} configurations, {n} frames, {s['jobs']} threads")
print(f"  views drawn once (reference, needbuffers) {s['view_seconds'] / n:8.4f} s per frame (wall)")
print(f"  shaded under every cache state            {s['recolor_seconds'] / n:8.4f} s per frame (wall)")
for key, value in sums.items():
    print(f"  {key:<10} {value / (n * runs):8.4f} s per configuration-frame (thread time)")
per_config_frame = s["wall_seconds"] / (n * runs)
print(f"  whole evaluation {s['wall_seconds']:.1f} s wall ({float(wall_eval):.1f} s with plots), "
      f"{per_config_frame:.4f} s per configuration-frame, peak RSS {int(peak) // 1024} MiB")
print(f"lone flight / evaluation, per configuration-frame: {alone / per_config_frame:.1f}x "
      f"(the lone flight on 1 thread, the evaluation on {cores})")
PY
