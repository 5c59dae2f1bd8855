#!/usr/bin/env bash
# The import graph's rules (scripts/check-imports.sh) hold for the repository, and the check
# fails on trees that break one, naming the file and line: the neutral layer src/render/
# including a renderer, the file format or the oracle including an encoder (only the tools
# encode), the two renderers including each other (one layer), and a folder with no layer.
#   tests/architecture/import_graph_test.sh SOURCE_DIR WORK_DIR
set -euo pipefail
source_dir=$1 work=$2
bash "$source_dir/scripts/check-imports.sh" "$source_dir"

# Plants FILE holding INCLUDE in an empty tree; the check must fail and name FILE:2.
expect_caught() {
  local file=$1 include=$2 output
  rm -rf "$work"
  mkdir -p "$work/$(dirname "$file")"
  printf '#pragma once\n#include "%s"\n' "$include" > "$work/$file"
  if output=$(bash "$source_dir/scripts/check-imports.sh" "$work" 2>&1); then
    echo "FAIL: check-imports accepted $file including $include: $output" >&2
    exit 1
  fi
  grep -q "^$file:2: " <<< "$output" || {
    echo "FAIL: the violation in $file is not named: $output" >&2
    exit 1
  }
}
expect_caught src/render/breaks_the_rule.h gl/headless_context.h
expect_caught src/format/breaks_the_rule.h build/texture_builder.h
expect_caught reference/breaks_the_rule.h build/block_encoding.h
expect_caught src/gl/breaks_the_rule.h reference/renderer.h
expect_caught reference/breaks_the_rule.h gl/gl_program.h

rm -rf "$work"
mkdir -p "$work/src/unplaced"
if output=$(bash "$source_dir/scripts/check-imports.sh" "$work" 2>&1); then
  echo "FAIL: check-imports accepted a folder with no layer: $output" >&2
  exit 1
fi
grep -q '^src/unplaced: no layer' <<< "$output" || {
  echo "FAIL: the folder with no layer is not named: $output" >&2
  exit 1
}
echo "PASS: the repository keeps the rules; src/render including gl/, src/format and reference/" \
  "including build/, gl/ and reference/ including each other and a folder with no layer are caught"
