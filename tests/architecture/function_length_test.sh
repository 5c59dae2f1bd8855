#!/usr/bin/env bash
# No function of src/ or reference/ is over 100 lines (scripts/check-function-length.sh), and the
# check fails on planted trees, naming file, line, function and length: a free function whose
# signature spans two lines, a member function defined inside its class, a constructor with brace
# initializers and a braced default argument, and a lambda at namespace scope, each 101 lines;
# while a function of exactly 100 lines, and one whose strings, characters, comments and inner
# lambdas hold unbalanced braces, pass.
#   tests/architecture/function_length_test.sh SOURCE_DIR WORK_DIR
set -euo pipefail
source_dir=$1 work=$2
check="$source_dir/scripts/check-function-length.sh"
bash "$check" "$source_dir"

# N statements, one a line.
statements() { for ((k = 0; k < $1; ++k)); do echo "  x += $k;"; done; }

rm -rf "$work"
mkdir -p "$work/src/planted" "$work/reference"
{
  echo '#include <string>'                      # 1
  echo 'namespace vt {'                         # 2
  echo 'int twoLineSignature(int x,'            # 3: 101 lines, 3 to 103
  echo '                     int y) {'
  statements 97
  echo '  return x + y;'
  echo '}'                                      # 103
  echo 'int exactlyAtTheLimit(int x) {'         # 104: 100 lines, 104 to 203
  statements 98
  echo '}'
  echo 'int bracesThatAreNotBlocks(int x) {'    # 204: 10 lines
  echo '  const std::string open = "{{{", close = R"(}})";'
  echo "  const char brace = '{';  // {"
  echo '  /* } } */'
  echo '  const auto inner = [&](int y) { return y + 1; };'
  echo '  if (x) {'
  echo '    x = inner(x) + brace + static_cast<int>(open.size() + close.size());'
  echo '  }'
  echo '  return x;'
  echo '}'                                      # 213
  echo '}  // namespace vt'
} > "$work/src/planted/functions.cpp"
{
  echo '#pragma once'                           # 1
  echo 'struct Options { int a = 0; };'         # 2
  echo 'class Planted {'                        # 3
  echo ' public:'                               # 4
  echo '  explicit Planted(Options options = {}) : a_{options.a}, b_(2) {'  # 5: 5 to 105
  statements 99
  echo '  }'                                    # 105
  echo '  int memberInside(int x) const {'      # 106: 106 to 206
  statements 99
  echo '  }'
  echo ' private:'
  echo '  int a_{0}, b_ = 0;'
  echo '};'
  echo 'inline const auto kLambda = [](int x) {'  # 210: 210 to 310
  statements 99
  echo '};'
} > "$work/reference/planted.h"

if output=$(bash "$check" "$work" 2>&1); then
  echo "FAIL: check-function-length accepted functions of 101 lines: $output" >&2
  exit 1
fi
expect() {
  grep -qF "$1 is 101 lines, over the limit of 100" <<< "$output" || {
    echo "FAIL: not named as '$1 is 101 lines': $output" >&2
    exit 1
  }
}
expect "src/planted/functions.cpp:3: twoLineSignature"
expect "reference/planted.h:5: Planted"
expect "reference/planted.h:106: memberInside"
expect "reference/planted.h:210: kLambda"
if [[ $(grep -c 'over the limit' <<< "$output") != 4 ]]; then
  echo "FAIL: more than the four planted functions named: $output" >&2
  exit 1
fi
echo "PASS: no function of src/ or reference/ is over 100 lines; planted functions of 101 lines" \
  "(two-line signature, member, constructor with brace initializers, lambda) are named, one of" \
  "100 and one with braces in literals and comments pass"
