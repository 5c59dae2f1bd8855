#!/usr/bin/env bash
# Redoes the thesis's chapter 4 on OpenArena maps and regenerates data/reports/chapter4.md:
# fetches the maps (scripts/fetch-openarena.sh), retextures and builds q3dm6ish, am_thornish and
# islandctf, makes the "prepared level" of 4.2.3.2 (the most used source image of each indoor map
# replaced by a flat image of its mean colour), runs `vt eval` with the configurations in
# data/chapter4/ over the storyboards in data/paths/, and writes the report with
# scripts/chapter4-report.py.
#   --size WxH      screen of every run (default 320x200)
#   --maps "A B"    indoor maps (default "q3dm6ish am_thornish")
#   --jobs N        runs at once (default: every core)
# Work files (textures of about 1-3 GB each, eval folders) go to $VT_DATA_CACHE/chapter4
# (default ~/.cache/vt/chapter4).
set -euo pipefail
cd "$(dirname "$0")/.."

size=320x200
maps="q3dm6ish am_thornish"
jobs=0
while (($#)); do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --maps) maps=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    *) echo "usage: scripts/reproduce-chapter4.sh [--size WxH] [--maps \"A B\"] [--jobs N]" >&2; exit 2 ;;
  esac
done

bash scripts/install-deps.sh
if [[ ! -x build/src/vt ]]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build --target vt
vt=$PWD/build/src/vt
baseoa=$(bash scripts/fetch-openarena.sh)
work=${VT_DATA_CACHE:-${HOME:-/tmp}/.cache/vt}/chapter4
mkdir -p "$work"

# Retextured and built once; `vt retexture` and `vt build` give the same bytes on every run.
prepare_map() {  # map
  local map=$1
  if [[ ! -f "$work/$map.vt" ]]; then
    "$vt" retexture "$map" --packages "$baseoa" -o "$work/$map" --no-coherence
    "$vt" build "$work/$map/$map.layout.json" -o "$work/$map.vt" -q
  fi
}

# The prepared level (4.2.3.2): the source image covering most texture area, made flat.
prepare_flat_level() {  # map
  local map=$1
  if [[ ! -f "$work/$map.prepared.vt" ]]; then
    python3 - "$work/$map" "$map" <<'PY'
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
    "$vt" build "$work/$map/$map.prepared.layout.json" -o "$work/$map.prepared.vt" -q
  fi
}

# A still camera at the storyboard's start (4.1.2: ancestor streaming is studied without motion).
still_path() {  # map
  python3 - "data/paths/$1.storyboard.json" "$work/$1.still.json" <<'PY'
import json, sys
story = json.load(open(sys.argv[1]))
json.dump({"start": story["start"], "storyboard": [{"kind": "hold", "frames": 240}]},
          open(sys.argv[2], "w"))
PY
}

evaluate() {  # texture mesh path configs title output
  "$vt" eval "$1" --mesh "$2" --path "$3" --configs "$4" --title "$5" --size "$size" \
    --jobs "$jobs" -o "$6"
}

results=$work/results
rm -rf "$results"
for map in $maps; do
  prepare_map "$map"
  prepare_flat_level "$map"
  still_path "$map"
  mesh=$work/$map/$map.obj
  evaluate "$work/$map.vt" "$mesh" "data/paths/$map.storyboard.json" data/chapter4/indoor.json \
    "$map" "$results/$map/indoor"
  evaluate "$work/$map.prepared.vt" "$mesh" "data/paths/$map.storyboard.json" \
    data/chapter4/prepared.json "$map, prepared level" "$results/$map/prepared"
  evaluate "$work/$map.vt" "$mesh" "$work/$map.still.json" data/chapter4/ancestors.json \
    "$map, still camera" "$results/$map/ancestors"
done
prepare_map islandctf
evaluate "$work/islandctf.vt" "$work/islandctf/islandctf.obj" data/paths/islandctf.storyboard.json \
  data/chapter4/terrain.json "islandctf terrain" "$results/islandctf/terrain"

python3 scripts/chapter4-report.py "$results" data/reports/chapter4.md
