#!/usr/bin/env bash
# The whole chapter-4 reproduction, timed (issue 19's target: at most 60 minutes and 8 GB on the
# project's 2-core machine): runs scripts/reproduce-chapter4.sh at 1024 x 768 into a scratch
# folder (the report, its figures and the `vt eval` folders; data/reports/ is left alone) and
# prints its wall time and peak memory, then each evaluation's configurations, frames, wall time
# and time per configuration-frame from its summary.json. The textures are built on the first
# run and kept in $VT_DATA_CACHE/chapter4 (about 20 GB): time a second run for the evaluation
# alone. Nothing else should run on the machine meanwhile.
#   usage: benchmarks/chapter4_reproduction.sh [--vt path/to/vt] [--keep DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
usage='usage: benchmarks/chapter4_reproduction.sh [--vt path/to/vt] [--keep DIR]'
vt=build/src/vt
keep=
while (($#)); do
  case "$1" in
    --vt) vt=$2; shift 2 ;;
    --keep) keep=$2; shift 2 ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
done
vt=$(realpath "$vt")
if [[ -n "$keep" ]]; then
  mkdir -p "$keep"
  work=$(realpath "$keep")
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi

/usr/bin/time -f "%e %M" -o "$work/reproduction.time" \
  bash scripts/reproduce-chapter4.sh --vt "$vt" --report "$work/report/chapter4.md" \
  --results "$work/results" > "$work/reproduction.log" 2>&1 ||
  { tail -20 "$work/reproduction.log" >&2; exit 1; }

python3 - "$work" "$(nproc)" <<'PY'
import glob, json, os, sys
work, cores = sys.argv[1], sys.argv[2]
wall, peak = open(os.path.join(work, "reproduction.time")).read().split()
print(f"scripts/reproduce-chapter4.sh at 1024 x 768 on {cores} cores: "
      f"{float(wall) / 60:.1f} minutes, peak RSS {int(peak) / 1024 / 1024:.2f} GiB")
total_runs = 0
for path in sorted(glob.glob(os.path.join(work, "results", "*", "*", "summary.json"))):
    s = json.load(open(path))
    runs, frames = len(s["runs"]), s["frames"]
    total_runs += runs * frames
    name = os.path.relpath(os.path.dirname(path), os.path.join(work, "results"))
    print(f"  {name:<24} {runs:3d} configurations x {frames:4d} frames  "
          f"{s['wall_seconds']:7.1f} s  {s['wall_seconds'] / (runs * frames) * 1000:6.2f} ms per "
          f"configuration-frame")
print(f"  {total_runs} configuration-frames in all")
PY
