#!/usr/bin/env bash
# The import graph's rules (ARCHITECTURE.md, "Rules at the seams"), checked over the #include lines
# of every source file: a folder may not include the folders listed after it. Prints each
# violation as file:line and exits 1 when there is one. Run by ctest (ImportGraph).
#   scripts/check-imports.sh [ROOT]     (default: the repository)
set -euo pipefail
root=${1:-$(dirname "$0")/..}
cd "$root"

# folder | folders its files may not include (as "folder/...")
rules=(
  "src/common|format render gl reference backends runtime eval verify calibrate capture cli"
  "src/format|render gl reference backends runtime eval verify calibrate capture cli"
  "src/render|gl reference backends runtime eval verify calibrate capture cli"
  "src/runtime|gl reference backends eval verify calibrate capture cli"
  "src/gl|reference backends eval verify calibrate cli"
  "reference|gl backends eval verify calibrate capture cli"
  "src/eval|gl reference verify calibrate capture cli"
  "src/retexture|gl reference eval verify calibrate capture cli"
  "src/capture|reference backends eval verify"
  "src/viewer|reference verify calibrate capture cli"
  "src/workflows|cli"
)

violations=0
for rule in "${rules[@]}"; do
  folder=${rule%%|*}
  [[ -d $folder ]] || continue
  read -r -a forbidden <<< "${rule#*|}"
  pattern=$(IFS='|'; echo "${forbidden[*]}")
  while IFS= read -r hit; do
    echo "$hit: $folder may not include ${hit##*#include }"
    violations=$((violations + 1))
  done < <(grep -rnE "^#include \"($pattern)/" "$folder" --include='*.h' --include='*.cpp' || true)
done
if ((violations > 0)); then
  echo "check-imports: $violations include(s) break the import graph's rules" >&2
  exit 1
fi
echo "check-imports: every include keeps the import graph's rules (${#rules[@]} folders)"
