#!/usr/bin/env bash
# Judges what gpu-run.sh brought back from the GPU machine, here where the oracle lives:
#   scripts/gpu-judge.sh OUT [KIT]   (default KIT: .gpu-kit)
# Fits the GPU's precision model from its probes (OUT/model.json; `vt calibrate` exits 1 and names
# the rule where the GPU breaks one), judges the captures under that model and under gl45
# (OUT/judged-*/summary.json) and prints a Markdown table of the verdicts and the frame times.
# VT_JUDGE_GL45=0 judges under the fitted model only (the GPU kit's test, which checks those rows).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=$(cd "${1:?usage: scripts/gpu-judge.sh OUT [KIT]}" && pwd)
kit=$(cd "${2:-$here/.gpu-kit}" && pwd)
vt=${VT:-$here/${VT_BUILD_DIR:-build}/src/vt}

unpacked=$out/unpacked
rm -rf "$unpacked"
mkdir -p "$unpacked"
for archive in "$out"/*.tar.gz; do tar -C "$unpacked" -xzf "$archive"; done

status=0
"$vt" calibrate --probes "$unpacked/probes" -o "$out/model.json" || status=$?
echo
echo "| captures | model | pixels | identical | explained | unexplained | ambiguous | colour width (1/255) | levels | pages |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for set in captures compressed/captures-bc1 compressed/captures-bc3a q3dm6ish stress \
  flight/rgba8 flight/linear-async flight/bc1; do
  [[ -d $unpacked/$set ]] || continue
  texture=scene.vt
  [[ $set == compressed/* ]] && texture=scene_${set#compressed/captures-}.vt
  [[ $set == flight/bc1 ]] && texture=scene_bc1.vt
  label=${set#compressed/}
  label=${label//\//-}
  ln -sf "$kit/data/$texture" "$unpacked/$set/$texture"
  models=(gl45)
  [[ -f $out/model.json ]] && models=("$out/model.json" gl45)
  [[ ${VT_JUDGE_GL45:-1} == 0 && -f $out/model.json ]] && models=("$out/model.json")
  for model in "${models[@]}"; do
    name=$(basename "$model" .json)
    report=$out/judged-$label-$name
    "$vt" crosscheck --captures "$unpacked/$set" --model "$model" --all-sets -o "$report" \
      >/dev/null ||
      status=1
    python3 - "$report/summary.json" "$label" "$name" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))["totals"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {s['pixels']} | {s['identical']} | {s['explained']} | "
      f"{s['unexplained']} | {s['ambiguous_fraction']:.4f} | {s['mean_color_width']:.2f} | "
      f"{s['mean_candidate_levels']:.2f} | {s['mean_candidate_pages']:.2f} |")
EOF
  done
done
for timings in "$out"/timings*.json; do
  [[ -f $timings ]] || continue
  python3 - "$timings" <<'EOF'
import json, sys
t = json.load(open(sys.argv[1]))
print(f"\n{t['renderer']} ({t['gl_version']}): {t['what']}, median of {t['repeats']}\n")
print("| size | view | mode | GPU ms | wall ms |")
print("|---|---|---|---|---|")
for f in t["frames"]:
    print(f"| {f['size']} | {f['view']} | {f['mode']} | {f['gpu_ms_median']:.3f} "
          f"({f['gpu_ms_min']:.3f}-{f['gpu_ms_max']:.3f}) | {f['wall_ms_median']:.3f} |")
EOF
done
exit "$status"
