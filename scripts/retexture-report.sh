#!/usr/bin/env bash
# Retextures the OpenArena maps the project uses with the thesis's layout and ours and prints the
# side-by-side table of docs/retexture.md (Markdown). Fetches the maps first (scripts/fetch-openarena.sh).
#   scripts/retexture-report.sh [BUILD_FOLDER] [OUTPUT_FOLDER]   (defaults: build, out/retexture)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
output=${2:-out/retexture}
packages=$(bash scripts/fetch-openarena.sh)
[[ -x "$build/src/vt" ]] || cmake --build "$build" --target vt >&2
for map in q3dm6ish dm6ish islandctf am_thornish; do
  "$build/src/vt" retexture "$map" --packages "$packages" -o "$output/$map" >&2
done
python3 - "$output" <<'PY'
import json, sys
folder = sys.argv[1]
print("| map | faces (patches) | textures | method | texture side | finest pages | pages, all levels | texels referenced | pages per 1000 pixels |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for name in ["q3dm6ish", "dm6ish", "islandctf", "am_thornish"]:
    r = json.load(open(f"{folder}/{name}/{name}.report.json"))
    for method, label in [("baseline", "thesis"), ("charts", "ours")]:
        m = r[method]
        print(f"| {name} | {r['faces']} ({r['patch_faces']}) | {r['textures']} | {label} | {m['side']} "
              f"| {m['finest_pages_allocated']} | {m['pages_allocated_all_levels']} "
              f"| {100 * m['referenced_fraction']:.1f}% | {m['pages_per_1000_pixels']:.3f} |")
PY
