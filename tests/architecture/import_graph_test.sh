#!/usr/bin/env bash
# The import graph's rules (scripts/check-imports.sh) hold for the repository, and the check
# fails on a tree that breaks one: a file of the neutral layer src/render/ including a renderer.
#   tests/architecture/import_graph_test.sh SOURCE_DIR WORK_DIR
set -euo pipefail
source_dir=$1 work=$2
bash "$source_dir/scripts/check-imports.sh" "$source_dir"

rm -rf "$work"
mkdir -p "$work/src/render"
printf '#pragma once\n#include "gl/headless_context.h"\n' > "$work/src/render/breaks_the_rule.h"
if output=$(bash "$source_dir/scripts/check-imports.sh" "$work" 2>&1); then
  echo "FAIL: check-imports accepted src/render including gl/: $output" >&2
  exit 1
fi
grep -q 'src/render/breaks_the_rule.h:2' <<< "$output" || {
  echo "FAIL: the violation is not named: $output" >&2
  exit 1
}
echo "PASS: the repository keeps the rules, and a renderer included by src/render is caught"
