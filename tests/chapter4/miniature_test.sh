#!/usr/bin/env bash
# The chapter-4 pipeline in miniature (scripts/reproduce-chapter4.sh --miniature): retexture and
# build q3dm6ish in our chart layout, `vt eval` two configurations over the storyboard's first
# motions, the report and the plots, and the same texture as BC1 flown against it. Checks that the
# report has a verdict table with bootstrap intervals, a compressed-pages section with its level
# table and paired intervals, and that the figures exist (SVG and PNG from `vt eval`, PNG in the
# report).
#   miniature_test.sh SOURCE_DIR VT SCRATCH
# Needs OpenArena's maps in $VT_OPENARENA_DIR (scripts/fetch-openarena.sh); without them the test
# is skipped (exit 77), except in CI (CI=true), where it fails. The built texture is kept in
# $VT_DATA_CACHE/chapter4 (default ~/.cache/vt/chapter4) like the full reproduction's, so only the
# first run pays for it.
set -euo pipefail
source_dir=$1 vt=$2 scratch=$3

if [[ -z "${VT_OPENARENA_DIR:-}" || ! -d "$VT_OPENARENA_DIR" ]]; then
  if [[ "${CI:-}" == true ]]; then
    echo "FAIL: VT_OPENARENA_DIR is not set in CI (scripts/fetch-openarena.sh)" >&2
    exit 1
  fi
  echo "SKIP: VT_OPENARENA_DIR names no folder of OpenArena's .pk3 archives"
  exit 77
fi

rm -rf "$scratch"
mkdir -p "$scratch"
report=$scratch/report/chapter4.md
bash "$source_dir/scripts/reproduce-chapter4.sh" --miniature --vt "$vt" --jobs 1 \
  --report "$report" --results "$scratch/results"

fail() { echo "FAIL: $*" >&2; exit 1; }
[[ -f "$report" ]] || fail "no report at $report"
grep -q '^| Claim (thesis) | Comparison: A − B, claimed side |' "$report" ||
  fail "the report has no verdict table"
# A row with a mean difference, an interval [low, high] and a computed verdict.
grep -Eq '\| [+-][0-9.]+e[+-][0-9]+ \| \[[+-][0-9.]+e[+-][0-9]+, [+-][0-9.]+e[+-][0-9]+\] \|.*\*\*(confirmed|contradicted|not resolved at this regime)\*\*' "$report" ||
  fail "no verdict row with a bootstrap interval"
grep -q 'Regime check' "$report" || fail "no regime check"
for figure in results/q3dm6ish/indoor/ssim results/q3dm6ish/indoor/budget; do
  for extension in svg png; do
    [[ -s "$scratch/$figure.$extension" ]] || fail "no figure $figure.$extension"
  done
done
# The report shows PNGs only.
[[ -s "$scratch/report/chapter4/q3dm6ish/claim01_1.png" ]] || fail "no figure claim01_1.png"
grep -q '(chapter4/q3dm6ish/claim01_1.png)' "$report" || fail "the report does not link claim01_1.png"
# Compressed pages: the levels compared, the runs, and paired differences with intervals.
grep -q '^## Compressed pages' "$report" || fail "no compressed-pages section"
grep -Eq '^\| 7 \| [0-9,]+ \| 0\.[0-9]{4} \| [0-9.]+ \| [0-9.]+ \|$' "$report" ||
  fail "no level table of the encoding's error"
grep -Eq '^\| \[BC1, equal bytes − RGBA8, PixelSum 5\].*\| [+-][0-9.]+e[+-][0-9]+ \| \[[+-][0-9.]+e[+-][0-9]+, [+-][0-9.]+e[+-][0-9]+\] \|' "$report" ||
  fail "no paired interval of BC1 at equal bytes against RGBA8"
[[ -s "$scratch/report/chapter4/q3dm6ish/compression/compression01.png" ]] ||
  fail "no figure compression01.png"
# Two configurations compared by hand (scripts/compare-configurations.py): the paired mean with its
# block-bootstrap interval and the gap closed; an unknown name is refused with exit 1.
python=${VT_PYTHON:-/usr/bin/python3}
compared=$("$python" "$source_dir/scripts/compare-configurations.py" \
  "$scratch/results/q3dm6ish/indoor" "PixelSum 10" "PixelSum 5" --between "PixelSum 5" "PixelSum 10")
grep -Eq '^PixelSum 10 - PixelSum 5: mean ssim [+-][0-9.]+e[+-][0-9]+, 95% interval \[[+-][0-9.]+e[+-][0-9]+, [+-][0-9.]+e[+-][0-9]+\], [0-9]+ frames in [0-9]+ blocks' <<<"$compared" ||
  fail "compare-configurations printed no interval: $compared"
grep -q '^PixelSum 10 closes 100% of the gap from PixelSum 5 to PixelSum 10' <<<"$compared" ||
  fail "compare-configurations: PixelSum 10 does not close its own gap: $compared"
if "$python" "$source_dir/scripts/compare-configurations.py" "$scratch/results/q3dm6ish/indoor" \
  "PixelSum 7" "PixelSum 5" 2>"$scratch/unknown.txt"; then
  fail "compare-configurations accepted an unknown configuration"
fi
grep -q "no configuration named 'PixelSum 7'" "$scratch/unknown.txt" ||
  fail "compare-configurations did not name the unknown configuration"
# The section beyond the thesis: a placeholder between its markers, which the beyond report
# replaces (here from the miniature's PixelSum runs as a "thesis layout": no frozen strategy or
# ceiling, so their cells are empty), once and again, never twice.
grep -q '^<!-- beyond the thesis: scripts/chapter4-beyond-report.py -->$' "$report" ||
  fail "no marker of the section beyond the thesis"
grep -q '^Not run: `bash scripts/reproduce-chapter4.sh` writes this section' "$report" ||
  fail "no placeholder of the section beyond the thesis"
mkdir -p "$scratch/beyond/q3dm6ish"
ln -s "$scratch/results/q3dm6ish/indoor" "$scratch/beyond/q3dm6ish/beyond-thesis"
for pass in 1 2; do
  "$python" "$source_dir/scripts/chapter4-beyond-report.py" "$scratch/beyond" \
    "$scratch/report/chapter4-beyond.md" "$report" >/dev/null
done
[[ $(grep -c '^## Beyond the thesis: which pages to stream$' "$report") == 1 ]] ||
  fail "the section beyond the thesis is not there once"
grep -Eq '^\| q3dm6ish \| thesis layout \(tuning\) \| [0-9.]+e[+-][0-9]+ \|' "$report" ||
  fail "no row of the section beyond the thesis"
grep -q '^## Compressed pages' "$report" || fail "the beyond section replaced what follows it"
grep -q 'Not run:' "$report" && fail "the placeholder stayed"
echo "miniature report: $report"
