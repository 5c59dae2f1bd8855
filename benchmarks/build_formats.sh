#!/usr/bin/env bash
# `vt build --format bc1` and `--format bc3` against the uncompressed build of the same generated
# 8192^2 RGB8 image (a four-corner colour gradient with uniform noise of 0.3 on top: smooth
# content and detail, both of which the block encoder must fit), each measured by GNU time in this
# script, one after the other: wall time, peak RSS and file size, and the ratios against rgba8
# (target: bc1 at most 3x the uncompressed build's time). Then the encoding's error on the finest
# level, RMS and PSNR against the uncompressed texture's (oiiotool --diff).
#   usage: benchmarks/build_formats.sh [path/to/vt]   (default build/src/vt)
set -euo pipefail
vt=$(realpath "${1:-build/src/vt}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
oiiotool --pattern fill:topleft=1,0,0:topright=0,1,0:bottomleft=0,0,1:bottomright=1,1,1 \
  8192x8192 3 --pattern noise:type=uniform:min=0:max=0.3:seed=7 8192x8192 3 --add -d uint8 \
  --compression none -o input.tif
declare -A seconds
for format in rgba8 bc1 bc3; do
  /usr/bin/time -f "%e %M" -o "$format.time" "$vt" build input.tif -o "$format.vt" \
    --format "$format" --quiet > "$format.log"
  read -r s kb < "$format.time"
  seconds[$format]=$s
  bytes=$(stat -c %s "$format.vt")
  echo "8192^2 RGB8 as $format: $s s, $((kb / 1024)) MiB peak RSS, $bytes bytes"
done
for format in bc1 bc3; do
  awk -v a="${seconds[$format]}" -v b="${seconds[rgba8]}" -v f="$format" \
    -v sa="$(stat -c %s "$format.vt")" -v sb="$(stat -c %s rgba8.vt)" 'BEGIN {
    printf "%s / rgba8: build time %.2fx (target for bc1 <= 3.0x), file size %.3fx\n", f, a / b, sa / sb }'
done
"$vt" export-level rgba8.vt --level 6 -o rgba8.png > /dev/null
for format in bc1 bc3; do
  "$vt" export-level "$format.vt" --level 6 -o "$format.png" > /dev/null
  # oiiotool --diff exits 1 when the images differ, which they do.
  { oiiotool rgba8.png --ch R,G,B "$format.png" --ch R,G,B --diff 2>&1 || true; } |
    awk -v f="$format" '/RMS error/ { rms = $4 } /Peak SNR/ { psnr = $4 }
      END { printf "%s finest level against rgba8: RMS %s, PSNR %s dB\n", f, rms, psnr }'
done
