#!/usr/bin/env bash
# vt build against its closest peer, OpenImageIO's maketx (a mip chain cut into tiles), on the same
# generated 16384^2 RGB8 image, both measured here by GNU time (wall time, peak RSS), and the
# ratios printed. Then a sparse 65536^2 layout (many images covering a small fraction of the area)
# whose peak RSS must stay under 1 GiB.
#   usage: benchmarks/build_vs_maketx.sh [path/to/vt]   (default build/src/vt)
set -euo pipefail
vt=$(realpath "${1:-build/src/vt}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# Uniform noise (no compression anywhere helps either tool), uncompressed TIFF.
oiiotool --pattern noise:type=uniform:min=0:max=1:seed=7 16384x16384 3 -d uint8 \
  --compression none -o input.tif

measure() {  # label, command...: prints "seconds kilobytes"
  local label=$1
  shift
  /usr/bin/time -f "%e %M" -o "$label.time" "$@" >"$label.log" 2>&1
  cat "$label.time"
}

read -r vt_s vt_kb < <(measure vt "$vt" build input.tif -o input.vt --quiet)
read -r tx_s tx_kb < <(measure maketx maketx input.tif -o input.tx)
echo "16384^2 RGB8: vt build $vt_s s, $((vt_kb / 1024)) MiB peak RSS; maketx $tx_s s, $((tx_kb / 1024)) MiB"
awk -v a="$vt_s" -v b="$tx_s" -v c="$vt_kb" -v d="$tx_kb" 'BEGIN {
  printf "vt build / maketx: wall time %.2fx (target <= 0.5x), peak RSS %.3fx (target <= 0.25x)\n", a / b, c / d }'

# 65536^2 sparse: 52 images of 512^2 on a 16 x 16 grid of 4096-texel cells (1.2% of the area).
oiiotool --pattern noise:type=uniform:min=0:max=1:seed=3 512x512 3 -d uint8 -o tile.png
{
  echo '{"page_size": 128, "border": 4, "side": 65536, "images": ['
  first=1
  for i in $(seq 0 15); do
    for j in $(seq 0 15); do
      (((i * 7 + j * 3) % 5 == 0)) || continue
      ((first)) || echo ','
      first=0
      echo "{\"file\": \"tile.png\", \"x\": $((i * 4096 + 100)), \"y\": $((j * 4096 + 300))}"
    done
  done
  echo ']}'
} >sparse.json
read -r sp_s sp_kb < <(measure sparse "$vt" build sparse.json -o sparse.vt --quiet)
echo "65536^2 sparse layout (52 images of 512^2): vt build $sp_s s, $((sp_kb / 1024)) MiB peak RSS (target < 1024 MiB)"
cat vt.log sparse.log
