#!/usr/bin/env bash
# A fingerprint of the oracle's result sets under gl45, for changes that must leave them exactly as
# they are (speed-ups of reference/result_set_builder.cpp and its callers). It crosschecks, each
# under --model gl45 on llvmpipe:
#   demo   the demo texture's named scenes ($VT_DEMO_DIR/scene.vt, default out/demo, from
#          scripts/demo.sh);
#   bc3    the same layout built as BC3 (block decoding free under gl45);
#   maps   q3dm6ish and am_thornish, every 200th storyboard frame at 480 x 270, where
#          benchmarks/oracle_vs_llvmpipe.sh has built them ($VT_BENCH_DIR, default
#          $VT_DATA_CACHE/oracle-bench).
# with every pixel's set (--all-sets), and prints the SHA-256 of each summary.json less its
# texture's path and the fields that say which pixels' sets were built (every pixel here). A
# summary holds the counts per reason, the ambiguous fraction and the mean widths to full double
# precision, so equal fingerprints before and after a change mean the same verdicts over the same
# sets, pixel counts and widths alike.
#   usage: scripts/set-fingerprint.sh [--check EXPECTED] [VT] [WORK]
#          (default build/src/vt, out/set-fingerprint)
# --check EXPECTED compares each fingerprint with EXPECTED's line for it ("<sha256>  <name>", as
# printed; tests/verify/set_fingerprints.txt holds the four), says "same" or "DIFFERS" for each,
# and exits 1 when one differs or demo or bc3 was not checked. A map not built here is left out.
set -euo pipefail
cd "$(dirname "$0")/.."
usage='usage: scripts/set-fingerprint.sh [--check EXPECTED] [VT] [WORK]'
expected=''
if [[ ${1:-} == --check ]]; then
  (($# >= 2)) || { echo "$usage" >&2; exit 2; }
  expected=$(realpath "$2")
  shift 2
fi
(($# <= 2)) || { echo "$usage" >&2; exit 2; }
vt=$(realpath "${1:-build/src/vt}")
work=${2:-out/set-fingerprint}
demo=${VT_DEMO_DIR:-out/demo}
[[ -x $vt ]] || { echo "$vt: no vt executable (build it first)" >&2; exit 1; }
[[ -f $demo/scene.vt ]] || { echo "$demo/scene.vt: missing (run scripts/demo.sh)" >&2; exit 1; }
[[ -z $expected || -f $expected ]] || { echo "$expected: no such file" >&2; exit 1; }
export LP_NUM_THREADS=${LP_NUM_THREADS:-2} EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
mkdir -p "$work"

if [[ ! -f $work/bc3.vt ]]; then
  "$vt" build "$demo/scene/layout.json" --format bc3 -o "$work/bc3.vt" -q
fi
checks=(demo bc3)
"$vt" crosscheck "$demo/scene.vt" --model gl45 --all-sets -o "$work/demo" > /dev/null
"$vt" crosscheck "$work/bc3.vt" --model gl45 --all-sets -o "$work/bc3" > /dev/null
bench=${VT_BENCH_DIR:-${VT_DATA_CACHE:-$HOME/.cache/vt}/oracle-bench}
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
differ=0
for check in "${checks[@]}"; do
  line=$(python3 - "$work/$check/summary.json" "$check" <<'PY'
import hashlib, json, sys
summary = json.load(open(sys.argv[1]))
summary.pop("texture", None)  # where WORK put it, not what the sets are
for record in [summary["totals"], *summary["frames"]]:
    record.pop("sets", None)  # "every pixel" (--all-sets)
    record.pop("set_pixels", None)  # then every pixel
digest = hashlib.sha256(json.dumps(summary, sort_keys=True).encode()).hexdigest()
print(f"{digest}  {sys.argv[2]}")
PY
)
  if [[ -z $expected ]]; then
    echo "$line"
  elif grep -qxF "$line" "$expected"; then
    echo "$line  same"
  else
    echo "$line  DIFFERS from $(grep -E "  $check\$" "$expected" || echo "no line for $check")"
    differ=$((differ + 1))
  fi
done
if [[ -n $expected ]] && ((differ > 0)); then
  echo "set-fingerprint: $differ of ${#checks[@]} fingerprints differ from $expected: the result" \
    "sets changed (if that is meant, store the new lines there and say why in the commit)" >&2
  exit 1
fi
