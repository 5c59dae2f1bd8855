#!/usr/bin/env bash
# The import graph's rules (docs/architecture.md, "Rules at the seams"), checked over the #include
# lines of every source file of src/ and reference/: one ordered list of layers, lowest first. A
# folder may include itself and the folders of lower layers only; folders on one layer are
# independent of each other (the oracle and the GL path never include each other). Every folder
# of src/ must have a layer, so that a new one is placed before it is used. Prints each violation
# as file:line and exits 1 when there is one. Run by ctest (ImportGraph).
#   scripts/check-imports.sh [ROOT]     (default: the repository)
set -euo pipefail
root=${1:-$(dirname "$0")/..}
cd "$root"

# Lowest first. A folder is src/NAME, except reference (reference/, whose public headers are
# included as "vt/...").
layers=(
  "common"                          # files, errors, checksums
  "format scene"                    # the file format; meshes, cameras and paths
  "shader"                          # the shader logic shared by GLSL and C++
  "render"                          # what both renderers share: cache state, frames, models
  "runtime gl reference"            # the streaming loop; the GL path; the CPU oracle
  "probes backends"                 # the calibration's probe draws; the renderer factory
  "capture eval retexture build"    # vt-capture's files; flights; vtgeo; the encoders
  "calibrate viewer"                # precision models from probes; `vt view`'s window
  "verify"                          # crosschecks of scenes and captures
  "workflows"                       # the commands' work, one call each
  "cli"                             # the command line
)
# Only the tools encode: build/ sits above format/, render/ and reference/, so that nothing a
# renderer or a reader is made of includes an encoder.

# Explicit exceptions, each "file|folder it may include": keep them few and say why.
exceptions=(
  # vt-capture is a program of its own; it shares the command line's size and camera validators
  # (cli/size_argument.cpp is compiled into it, src/CMakeLists.txt).
  "src/capture/main.cpp|cli"
)

declare -A layer_of
for ((i = 0; i < ${#layers[@]}; ++i)); do
  for folder in ${layers[i]}; do layer_of[$folder]=$i; done
done
path_of() { [[ $1 == reference ]] && echo reference || echo "src/$1"; }

violations=0
# Every folder of src/ (and reference/) has a layer.
for dir in src/*/; do
  folder=$(basename "$dir")
  if [[ -z ${layer_of[$folder]+set} ]]; then
    echo "src/$folder: no layer (add it to the list in scripts/check-imports.sh)"
    violations=$((violations + 1))
  fi
done

for folder in "${!layer_of[@]}"; do
  dir=$(path_of "$folder")
  [[ -d $dir ]] || continue
  own=${layer_of[$folder]}
  while IFS= read -r hit; do
    file=${hit%%:*}
    rest=${hit#*:}
    line=${rest%%:*}
    [[ $rest =~ ^[0-9]+:[[:space:]]*#[[:space:]]*include[[:space:]]*\"([^/\"]+)/ ]] || continue
    included=${BASH_REMATCH[1]}
    [[ $included == vt ]] && included=reference  # the oracle's public API
    [[ $included == "$folder" || -z ${layer_of[$included]+set} ]] && continue
    ((layer_of[$included] < own)) && continue
    excepted=false
    for exception in "${exceptions[@]}"; do
      [[ $exception == "$file|$included" ]] && excepted=true
    done
    $excepted && continue
    if ((layer_of[$included] == own)); then
      why="its own layer's $included"
    else
      why="$included, a higher layer"
    fi
    echo "$file:$line: $folder may not include $why (${hit##*#include })"
    violations=$((violations + 1))
  done < <(grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^/"]+/' "$dir" \
             --include='*.h' --include='*.cpp' --include='*.glsl' || true)
done
if ((violations > 0)); then
  echo "check-imports: $violations include(s) break the import graph's rules" >&2
  exit 1
fi
echo "check-imports: every include keeps the import graph's rules (${#layer_of[@]} folders in" \
  "${#layers[@]} layers)"
