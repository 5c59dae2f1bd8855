#!/usr/bin/env bash
# Redoes the thesis's chapter 4 on OpenArena maps and regenerates data/reports/chapter4.md:
# fetches the maps (scripts/fetch-openarena.sh), retextures and builds q3dm6ish, am_thornish and
# islandctf, makes the "prepared level" of 4.2.3.2 (the most used source image of each indoor map
# replaced by a flat image of its mean colour), runs `vt eval` with the configurations in
# data/chapter4/ over the storyboards in data/paths/, and writes the report with
# scripts/chapter4-report.py. Last per indoor map, compressed pages: its chart layout as BC1
# against RGBA8 (the function `compression` below says how).
#
# The indoor maps are flown on the thesis's own layout (`vt retexture --method baseline`, every
# face its own area: $work/MAP.baseline.vt) with indoor.json, prepared.json and ancestors.json;
# our chart layout ($work/MAP.vt) is an extra column, flown with charts.json. The terrain keeps the
# chart layout: the thesis overlaid its terrains' triangle network with one continuous area of the
# texture (4.4), which our charts keep and the per-face baseline would cut apart.
#   --size WxH      screen of every run (default 1024x768, the thesis's)
#   --maps "A B"    indoor maps (default "q3dm6ish am_thornish")
#   --jobs N        runs at once (default: every core)
#   --report PATH   where the report goes (default data/reports/chapter4.md); its figures go to
#                   PATH's folder / chapter4
#   --results DIR   where the `vt eval` folders go, emptied first (default $work/results; with
#                   --miniature, next to the report: REPORT without .md, plus .results)
#   --vt PATH       use this vt binary: no dependency check, no build
#   --beyond        only page selection beyond the thesis (data/chapter4/beyond.json: the ceiling
#                   of selection and the strategy frozen on q3dm6ish's thesis layout) on both
#                   indoor layouts and the terrain, into data/reports/chapter4-beyond.md and its
#                   section of the report (scripts/chapter4-beyond-report.py); the full run flies
#                   them inside its indoor, chart and terrain evaluations and writes both
#   --miniature     the whole pipeline (retexture, build, eval, report, plots) in under a minute,
#                   for CI: q3dm6ish only, its storyboard cut to the motions that start within the
#                   first 40 frames, 160x100, PixelSum 5 and 10 (data/chapter4/miniature.json) on
#                   our chart layout (1 GB and 6 s to build, against the thesis layout's 2.4 GB and
#                   about a minute), and its BC1 build (125 MB, 5 s) against it; no prepared
#                   level, still camera, chart column or terrain. Use it with --report.
# Work files (textures of about 1-3 GB each, eval folders) go to $VT_DATA_CACHE/chapter4
# (default ~/.cache/vt/chapter4); $VT_OPENARENA_DIR names the maps' .pk3 folder instead of
# fetching them.
set -euo pipefail

size=1024x768
maps="q3dm6ish am_thornish"
jobs=0
report=data/reports/chapter4.md
results=
vt=
miniature=false
beyond_only=false
usage='usage: scripts/reproduce-chapter4.sh [--size WxH] [--maps "A B"] [--jobs N] [--report PATH] [--results DIR] [--vt PATH] [--beyond] [--miniature]'
while (($#)); do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --maps) maps=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --report) report=$2; shift 2 ;;
    --results) results=$2; shift 2 ;;
    --vt) vt=$(realpath "$2"); shift 2 ;;
    --miniature) miniature=true; shift ;;
    --beyond) beyond_only=true; shift ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
done
# Paths given relative to the caller's folder, before the `cd` below.
report=$(realpath -m "$report")
[[ -z "$results" ]] || results=$(realpath -m "$results")
cd "$(dirname "$0")/.."
if $miniature; then
  # 160 x 100 keeps the reference images and both flights at a few seconds each.
  size=160x100
  maps=q3dm6ish
fi

if [[ -z "$vt" ]]; then
  bash scripts/install-deps.sh
  if [[ ! -x build/src/vt ]]; then
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
  fi
  cmake --build build --target vt
  vt=$PWD/build/src/vt
fi
# Debian's python3 has python3-matplotlib (scripts/install-deps.sh); $VT_PYTHON overrides it, as
# for the plots of `vt eval`.
if [[ -n "${VT_PYTHON:-}" ]]; then
  python=$VT_PYTHON
elif [[ -x /usr/bin/python3 ]]; then
  python=/usr/bin/python3
else
  python=python3
fi
baseoa=${VT_OPENARENA_DIR:-$(bash scripts/fetch-openarena.sh)}
work=${VT_DATA_CACHE:-${HOME:-/tmp}/.cache/vt}/chapter4
if $miniature; then
  results=${results:-${report%.md}.results}  # never over the full run's results
elif $beyond_only; then
  results=${results:-$work/results-beyond}
else
  results=${results:-$work/results}
fi
mkdir -p "$work"

# Retextured and built once; `vt retexture` and `vt build` give the same bytes on every run.
# Our chart layout: $work/MAP/ and $work/MAP.vt; the thesis's: $work/MAP.baseline/ and .vt.
prepare_map() {  # map [method]
  local map=$1 method=${2:-charts} name=$1
  [[ $method == charts ]] || name=$map.$method
  if [[ ! -f "$work/$name.vt" ]]; then
    "$vt" retexture "$map" --packages "$baseoa" -o "$work/$name" --no-coherence --method "$method"
    "$vt" build "$work/$name/$map.layout.json" -o "$work/$name.vt" -q
  fi
}

# The prepared level (4.2.3.2): the source image covering most texture area, made flat.
prepare_flat_level() {  # map name (the texture's folder and file stem in $work)
  local map=$1 name=$2
  if [[ ! -f "$work/$name.prepared.vt" ]]; then
    "$python" - "$work/$name" "$map" <<'PY'
import collections, json, os, subprocess, sys
folder, name = sys.argv[1], sys.argv[2]
layout = json.load(open(os.path.join(folder, name + ".layout.json")))
area = collections.Counter()
for image in layout["images"]:
    area[image["file"]] += image.get("width", 0) * image.get("height", 0)
file = area.most_common(1)[0][0]
source = os.path.join(folder, file)
stats = subprocess.run(["oiiotool", "--stats", source], capture_output=True, text=True,
                       check=True).stdout
line = next(l for l in stats.splitlines() if "Stats Avg:" in l)
scale = 255.0 if "(of 255)" in line else 1.0  # integer images report averages in their units
values = [float(v) / scale for v in line.split("Avg:")[1].split("(")[0].split()][:3]
while len(values) < 3:
    values.append(values[0])
spec = subprocess.run(["oiiotool", "--info", source], capture_output=True, text=True,
                      check=True).stdout
width, height = [int(v) for v in spec.split(":")[1].split(",")[0].split("x")]
flat = "images/prepared_flat.png"
subprocess.run(["oiiotool", "--pattern", "constant:color=" + ",".join(f"{v:.6f}" for v in values),
                f"{width}x{height}", "3", "-d", "uint8", "-o", os.path.join(folder, flat)],
               check=True)
for image in layout["images"]:
    if image["file"] == file:
        image["file"] = flat
json.dump(layout, open(os.path.join(folder, name + ".prepared.layout.json"), "w"))
print(f"prepared level of {name}: {file} ({area[file]} texels placed) made flat")
PY
    "$vt" build "$work/$name/$map.prepared.layout.json" -o "$work/$name.prepared.vt" -q
  fi
}

# A still camera at the storyboard's start (4.1.2: ancestor streaming is studied without motion).
still_path() {  # map
  "$python" - "data/paths/$1.storyboard.json" "$work/$1.still.json" <<'PY'
import json, sys
story = json.load(open(sys.argv[1]))
json.dump({"start": story["start"], "storyboard": [{"kind": "hold", "frames": 240}]},
          open(sys.argv[2], "w"))
PY
}

# The miniature's storyboard: the entries that start within the first 40 frames, whole (on
# q3dm6ish: the hold, the stop, the hold after it and the slow turn back, 46 frames; enough
# segments for a bootstrap interval).
short_path() {  # map output
  "$python" - "data/paths/$1.storyboard.json" "$2" <<'PY'
import json, sys
story = json.load(open(sys.argv[1]))
kept, frames = [], 0
for entry in story["storyboard"]:
    if frames >= 40:
        break
    kept.append(entry)
    frames += entry["frames"]
story["storyboard"] = kept
json.dump(story, open(sys.argv[2], "w"))
PY
}

evaluate() {  # texture mesh path configs title output [vt eval options]
  "$vt" eval "$1" --mesh "$2" --path "$3" --configs "$4" --title "$5" --size "$size" \
    --jobs "$jobs" -o "$6" "${@:7}"
}

# The cache of the motion experiments, per map (N x N frames of 128 x 128 texels): a real
# constraint for the larger budget, and as large as the regime check needs. The largest frame
# needs 641 pages on am_thornish and 264 on q3dm6ish, but what fills a cache is the pages a whole
# storyboard streams (PixelSum 10: about 2240 on am_thornish, 1840 to 1880 on q3dm6ish). With smaller
# caches the larger budget evicts pages the camera comes back to and loses on those motions:
# am_thornish at 40 x 40 (its turn to the ramp), q3dm6ish at 36 x 36 (its walk back east). Each is
# the smallest cache of scripts/chapter4-cache-sweep.sh where the regime check holds and only the
# larger budget evicts (that script prints the check and the evictions at seven sizes); the
# report states the cache against the working set and how many runs evicted.
declare -A cache_frames=([am_thornish]=48 [q3dm6ish]=40)
cache_of() {  # map
  echo "${cache_frames[$1]:-48}"
}

# Compressed pages (the thesis's conclusion): the chart layout also built as BC1, both builds
# timed, its levels compared with the uncompressed ones (`vt info --against`), and flown under
# PixelSum, judged against the uncompressed texture's references (`vt eval --reference-texture`):
# at the cache and link bytes of the chart experiment's PixelSum 5 (BC1 pages are 6 to 8 times
# smaller, so more of them), and at its pages. The uncompressed run is charts' own PixelSum 5.
# The miniature (timed=false) builds BC1 without timing an RGBA8 build against it (1 GB more).
compression() {  # map cache_frames path timed
  local map=$1 frames=$2 path=$3 timed=$4 out=$results/$1/compression
  mkdir -p "$out"
  local t0 t1 t2 rgba8_bytes
  t0=$(date +%s.%N)
  if $timed; then
    "$vt" build "$work/$map/$map.layout.json" -o "$out/timing.rgba8.vt" -q
    rgba8_bytes=$(stat -c %s "$out/timing.rgba8.vt")
    rm -f "$out/timing.rgba8.vt"
  else
    rgba8_bytes=$(stat -c %s "$work/$map.vt")
  fi
  t1=$(date +%s.%N)
  "$vt" build "$work/$map/$map.layout.json" -o "$work/$map.bc1.vt" --format bc1 -q
  t2=$(date +%s.%N)
  "$vt" info "$work/$map.bc1.vt" --against "$work/$map.vt" --json > "$out/levels.json"
  "$vt" info "$work/$map.vt" --json > "$out/rgba8.json"
  "$python" - "$out" "$frames" "$t0" "$t1" "$t2" "$rgba8_bytes" "$work/$map.bc1.vt" "$timed" <<'PY'
import json, os, sys
out, frames, t0, t1, t2, rgba8_bytes, bc1, timed = sys.argv[1:]
frames = int(frames)
page = json.load(open(os.path.join(out, "rgba8.json")))["page_bytes"]
json.dump({"rgba8_seconds": float(t1) - float(t0) if timed == "true" else None,
           "bc1_seconds": float(t2) - float(t1),
           "rgba8_bytes": int(rgba8_bytes), "bc1_bytes": os.path.getsize(bc1),
           "cache_frames": frames, "rgba8_page_bytes": page},
          open(os.path.join(out, "build.json"), "w"), indent=1)
# The chart experiment's defaults (data/chapter4/charts.json), PixelSum at 5 RGBA8 pages a frame.
json.dump({"defaults": {"budget": 5, "initial_levels": 3, "preload_visible": True},
           "configurations": [
               {"name": "BC1, equal bytes", "heuristic": "pixelsum", "budget_bytes": 5 * page,
                "cache_bytes": frames * frames * page},
               {"name": "BC1, equal pages", "heuristic": "pixelsum"}]},
          open(os.path.join(out, "configs.json"), "w"), indent=1)
PY
  evaluate "$work/$map.bc1.vt" "$work/$map/$map.obj" "$path" "$out/configs.json" \
    "$map, BC1 against RGBA8" "$out/eval" --cache-frames "$frames" \
    --reference-texture "$work/$map.vt"
}

# The configurations of data/chapter4/beyond.json that CONFIGS lacks, added to them into OUTPUT:
# the full run flies page selection beyond the thesis inside the thesis's own evaluations, so that
# the views are drawn once and PixelSum 5 and 10 and the combination flown once for both reports.
# The defaults must agree but for the cache, which is the evaluation's (`--beyond` flies each map
# at the cache of its thesis experiments too); a name in both must name the same configuration.
with_beyond() {  # configs output
  "$python" - "$1" data/chapter4/beyond.json "$2" <<'PY'
import json, sys
own, beyond, output = sys.argv[1:]
a, b = json.load(open(own)), json.load(open(beyond))
def but_cache(defaults):
    return {k: v for k, v in (defaults or {}).items() if k != "cache_frames"}
if but_cache(a.get("defaults")) != but_cache(b.get("defaults")):
    sys.exit(f"{own} and {beyond} have different defaults")
named = {c["name"]: c for c in a["configurations"]}
for c in b["configurations"]:
    if c["name"] not in named:
        a["configurations"].append(c)
    elif named[c["name"]] != c:
        sys.exit(f"{own} and {beyond} define {c['name']!r} differently")
json.dump(a, open(output, "w"), indent=1)
PY
}

# Page selection beyond the thesis alone (--beyond; issue 51): the ceiling and the frozen strategy
# against PixelSum 5 and 10 on each indoor map's two layouts and on the terrain, each layout an
# evaluation of its own. The report goes beside chapter4.md, its verdicts into a section of it.
beyond() {
  local map cache
  for map in $maps; do
    prepare_map "$map" baseline
    prepare_map "$map"
    cache=(--cache-frames "$(cache_of "$map")")
    evaluate "$work/$map.baseline.vt" "$work/$map.baseline/$map.obj" \
      "data/paths/$map.storyboard.json" data/chapter4/beyond.json "$map, beyond the thesis" \
      "$results/$map/beyond-thesis" "${cache[@]}"
    evaluate "$work/$map.vt" "$work/$map/$map.obj" "data/paths/$map.storyboard.json" \
      data/chapter4/beyond.json "$map, chart layout, beyond the thesis" \
      "$results/$map/beyond-charts" "${cache[@]}"
  done
  prepare_map islandctf
  evaluate "$work/islandctf.vt" "$work/islandctf/islandctf.obj" \
    data/paths/islandctf.storyboard.json data/chapter4/beyond.json \
    "islandctf, beyond the thesis" "$results/islandctf/beyond-terrain" --cache-frames 40
  "$python" scripts/chapter4-beyond-report.py "$results" "$(dirname "$report")/chapter4-beyond.md" \
    "$report"
}

rm -rf "$results"
if $beyond_only; then
  beyond
  exit 0
fi
if $miniature; then
  prepare_map q3dm6ish
  mkdir -p "$results"
  short_path q3dm6ish "$results/q3dm6ish.short.json"
  evaluate "$work/q3dm6ish.vt" "$work/q3dm6ish/q3dm6ish.obj" \
    "$results/q3dm6ish.short.json" data/chapter4/miniature.json "q3dm6ish, miniature" \
    "$results/q3dm6ish/indoor"
  compression q3dm6ish 32 "$results/q3dm6ish.short.json" false  # miniature.json's cache
  "$python" scripts/chapter4-report.py "$results" "$report"
  exit 0
fi
# The full run: the thesis's experiments, page selection beyond the thesis inside the indoor
# (thesis layout), chart and terrain evaluations, then both reports.
mkdir -p "$results"
for map in $maps; do
  prepare_map "$map" baseline
  prepare_map "$map"
  prepare_flat_level "$map" "$map.baseline"
  still_path "$map"
  mesh=$work/$map.baseline/$map.obj
  cache=(--cache-frames "$(cache_of "$map")")
  with_beyond data/chapter4/indoor.json "$results/$map.indoor.json"
  with_beyond data/chapter4/charts.json "$results/$map.charts.json"
  evaluate "$work/$map.baseline.vt" "$mesh" "data/paths/$map.storyboard.json" \
    "$results/$map.indoor.json" "$map" "$results/$map/indoor" "${cache[@]}"
  evaluate "$work/$map.baseline.prepared.vt" "$mesh" "data/paths/$map.storyboard.json" \
    data/chapter4/prepared.json "$map, prepared level" "$results/$map/prepared" "${cache[@]}"
  evaluate "$work/$map.baseline.vt" "$mesh" "$work/$map.still.json" data/chapter4/ancestors.json \
    "$map, still camera" "$results/$map/ancestors"
  evaluate "$work/$map.vt" "$work/$map/$map.obj" "data/paths/$map.storyboard.json" \
    "$results/$map.charts.json" "$map, chart layout" "$results/$map/charts" "${cache[@]}"
  compression "$map" "$(cache_of "$map")" "data/paths/$map.storyboard.json" true
done
prepare_map islandctf
with_beyond data/chapter4/terrain.json "$results/islandctf.terrain.json"
evaluate "$work/islandctf.vt" "$work/islandctf/islandctf.obj" data/paths/islandctf.storyboard.json \
  "$results/islandctf.terrain.json" "islandctf terrain" "$results/islandctf/terrain"

"$python" scripts/chapter4-report.py "$results" "$report"
"$python" scripts/chapter4-beyond-report.py "$results" "$(dirname "$report")/chapter4-beyond.md" \
  "$report"
