#!/usr/bin/env bash
# What an NVIDIA H100 drew with the GPU kit (data/gpus/nvidia-h100), judged here without a GPU:
# its probes calibrate to the committed model, which breaks no rule, and its captures of the named
# scenes have no unexplained pixel under that model nor under gl45. A change to the fitting or to
# the result sets that would misjudge this GPU fails here.
#   h100_evidence_test.sh SOURCE VT WORK
set -euo pipefail
source=$1 vt=$2 work=$3
evidence=$source/data/gpus/nvidia-h100
rm -rf "$work"
mkdir -p "$work"
tar -C "$work" -xzf "$evidence/probes.tar.gz"
tar -C "$work" -xzf "$evidence/captures.tar.gz"
# The dense BC3 alpha table beside the probes pins the alpha palette's weights (decoding_fit.h).
cp "$evidence/bc3-alpha.u8" "$work/probes/"

"$vt" calibrate --probes "$work/probes" -o "$work/model.json" >"$work/calibrate.txt" 2>&1 || {
  cat "$work/calibrate.txt"
  echo "FAIL: the H100's probes no longer calibrate (above)"
  exit 1
}
cmp "$work/model.json" "$evidence/model.json" || {
  echo "FAIL: the H100's probes give another model than data/gpus/nvidia-h100/model.json;"
  echo "      if the change is meant, rewrite it: vt calibrate --probes DIR -o model.json"
  exit 1
}

# The captures name the demo's texture (vt demo, deterministic) as scene.vt.
"$vt" demo --output "$work/demo" >/dev/null
ln -s "$work/demo/scene.vt" "$work/captures/scene.vt"
for model in "$evidence/model.json" gl45; do
  "$vt" crosscheck --captures "$work/captures" --model "$model" -o "$work/judged" |
    tail -1 | tee "$work/verdict.txt"
  grep -q "of 1024000 pixels identical, [0-9]* explained, 0 unexplained" "$work/verdict.txt" || {
    echo "FAIL: the H100's captures are not all explained under $model"
    exit 1
  }
done
echo "h100 evidence: model and verdicts as committed"
