#!/usr/bin/env bash
# q3dm6ish retextured and built once for every Release test that flies, renders or checks it
# (ctest fixture q3dm6ish, tests/CMakeLists.txt): `vt retexture q3dm6ish` into OUT/q3 and `vt build`
# of its layout into OUT/q3.vt, as test::retextureAndBuildQ3dm6ish does for a test alone, which
# links these instead when VT_Q3DM6ISH_DIR names OUT. Without $VT_OPENARENA_DIR nothing is made and
# each test skips (fails in CI) as before. Written into a scratch folder and renamed, so a folder
# OUT that exists is complete.
#   tests/openarena/shared_q3dm6ish.sh VT OUT
set -euo pipefail
vt=$1 out=$2
rm -rf "$out" "$out.partial"
if [[ -z ${VT_OPENARENA_DIR:-} ]]; then
  echo "VT_OPENARENA_DIR not set: no shared q3dm6ish"
  exit 0
fi
mkdir -p "$out.partial"
"$vt" retexture q3dm6ish --packages "$VT_OPENARENA_DIR" -o "$out.partial/q3" --no-coherence \
  >/dev/null
"$vt" build "$out.partial/q3/q3dm6ish.layout.json" -o "$out.partial/q3.vt" -q
mv "$out.partial" "$out"
echo "q3dm6ish retextured and built into $out"
