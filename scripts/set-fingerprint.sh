#!/usr/bin/env bash
# A fingerprint of the oracle's result sets under gl45, for changes that must leave them exactly as
# they are (speed-ups of reference/result_set_builder.cpp and its callers). It crosschecks, each
# under --model gl45 on llvmpipe:
#   demo   the demo texture's named scenes (out/demo/scene.vt, from scripts/demo.sh);
#   bc3    the same layout built as BC3 (block decoding free under gl45);
#   maps   q3dm6ish and am_thornish, every 200th storyboard frame at 480 x 270, where
#          benchmarks/oracle_vs_llvmpipe.sh has built them ($VT_DATA_CACHE/oracle-bench).
# with every pixel's set (--all-sets), and prints the SHA-256 of each summary.json less its
# texture's path and the fields that say which pixels' sets were built (every pixel here). A
# summary holds the counts per reason, the ambiguous fraction and the mean widths to full double
# precision, so equal fingerprints before and after a change mean the same verdicts over the same
# sets, pixel counts and widths alike.
#   usage: scripts/set-fingerprint.sh [VT] [WORK]   (default build/src/vt, out/set-fingerprint)
set -euo pipefail
cd "$(dirname "$0")/.."
usage='usage: scripts/set-fingerprint.sh [VT] [WORK]'
(($# <= 2)) || { echo "$usage" >&2; exit 2; }
vt=$(realpath "${1:-build/src/vt}")
work=${2:-out/set-fingerprint}
[[ -x $vt ]] || { echo "$vt: no vt executable (build it first)" >&2; exit 1; }
[[ -f out/demo/scene.vt ]] || { echo "out/demo/scene.vt: missing (run scripts/demo.sh)" >&2; exit 1; }
export LP_NUM_THREADS=${LP_NUM_THREADS:-2} EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
mkdir -p "$work"

if [[ ! -f $work/bc3.vt ]]; then
  "$vt" build out/demo/scene/layout.json --format bc3 -o "$work/bc3.vt" -q
fi
checks=(demo bc3)
"$vt" crosscheck out/demo/scene.vt --model gl45 --all-sets -o "$work/demo" > /dev/null
"$vt" crosscheck "$work/bc3.vt" --model gl45 --all-sets -o "$work/bc3" > /dev/null
bench=${VT_DATA_CACHE:-$HOME/.cache/vt}/oracle-bench
for map in q3dm6ish am_thornish; do
  if [[ ! -f $bench/$map.vt ]]; then
    echo "$map: not built (benchmarks/oracle_vs_llvmpipe.sh builds it); left out" >&2
    continue
  fi
  "$vt" crosscheck "$bench/$map.vt" --mesh "$bench/$map/$map.obj" \
    --path "data/paths/$map.storyboard.json" --every 200 --size 480x270 --model gl45 --all-sets \
    -o "$work/$map" > /dev/null
  checks+=("$map")
done
for check in "${checks[@]}"; do
  python3 - "$work/$check/summary.json" "$check" <<'PY'
import hashlib, json, sys
summary = json.load(open(sys.argv[1]))
summary.pop("texture", None)  # where WORK put it, not what the sets are
for record in [summary["totals"], *summary["frames"]]:
    record.pop("sets", None)  # "every pixel" (--all-sets)
    record.pop("set_pixels", None)  # then every pixel
digest = hashlib.sha256(json.dumps(summary, sort_keys=True).encode()).hexdigest()
print(f"{digest}  {sys.argv[2]}")
PY
done
