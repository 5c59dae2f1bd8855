#!/usr/bin/env bash
# The oracle's gl45 result sets are those the history vouches for: scripts/set-fingerprint.sh's
# four fingerprints (the demo's named scenes, their layout as BC3, q3dm6ish and am_thornish) equal
# tests/verify/set_fingerprints.txt. The demo's texture is made here (vt demo); the two maps are
# retextured and built here as benchmarks/oracle_vs_llvmpipe.sh builds them, where OpenArena is
# at hand ($VT_OPENARENA_DIR, which CI exports), and removed afterwards (about 4 GB). Without it,
# demo and bc3 only. About 80 s on two cores, most of it the maps.
#   tests/verify/set_fingerprints_test.sh SOURCE_DIR VT WORK_DIR
set -euo pipefail
source_dir=$1 vt=$2 work=$3
export LP_NUM_THREADS=${LP_NUM_THREADS:-2} EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
rm -rf "$work"
mkdir -p "$work"
"$vt" demo --output "$work/demo" > /dev/null

maps=$work/maps
mkdir -p "$maps"
trap 'rm -f "$maps"/*.vt' EXIT
if [[ -n ${VT_OPENARENA_DIR:-} ]]; then
  for map in q3dm6ish am_thornish; do
    # q3dm6ish as the ctest fixture made it once for every test (tests/openarena/), where it did.
    if [[ $map == q3dm6ish && -f ${VT_Q3DM6ISH_DIR:-}/q3.vt ]]; then
      ln -s "$VT_Q3DM6ISH_DIR/q3" "$maps/$map"
      ln -s "$VT_Q3DM6ISH_DIR/q3.vt" "$maps/$map.vt"
      continue
    fi
    "$vt" retexture "$map" --packages "$VT_OPENARENA_DIR" -o "$maps/$map" --no-coherence > /dev/null
    "$vt" build "$maps/$map/$map.layout.json" -o "$maps/$map.vt" -q
  done
else
  echo "VT_OPENARENA_DIR not set: q3dm6ish and am_thornish left out (run" \
    "scripts/fetch-openarena.sh and export it)"
fi
VT_DEMO_DIR=$work/demo VT_BENCH_DIR=$maps bash "$source_dir/scripts/set-fingerprint.sh" \
  --check "$source_dir/tests/verify/set_fingerprints.txt" "$vt" "$work/fingerprints"
