#!/usr/bin/env bash
# docs/commands.md says what `--help` says: every subcommand of vt and vt-capture has a section
# ("## vt build", "## vt golden check", ...) whose table has a row for each option its --help
# prints (the first cell as "`-o, --output`") and none for an option it does not; no section
# names a subcommand that does not exist.
#   tests/docs/commands_reference_test.sh SOURCE_DIR VT VT_CAPTURE
set -euo pipefail
source_dir=$1 vt=$2 vt_capture=$3
doc=$source_dir/docs/commands.md
failures=0 checked=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# The names CLI11 lists under "Subcommands:" in a help text, one a line.
subcommands_in() { awk '/^Subcommands:/ {s = 1; next} s && /^  [a-z]/ {print $1}' <<< "$1"; }
# The option names under "Options:" (both spellings of "-o,--output"), --help left out.
options_in() {
  awk '/^[A-Za-z]+:/ {s = ($0 ~ /^Options:/); next}
       s && /^  -/ {n = split($1, names, ","); for (i = 1; i <= n; i++) print names[i]}' <<< "$1" |
    grep -vx -e '-h' -e '--help' || true
}
# The lines of docs/commands.md from "## NAME" to the next "## ".
section_of() { awk -v h="## $1" '$0 == h {s = 1; next} s && /^## / {exit} s' "$doc"; }

# Whether LINES (one item a line) holds ITEM; without a process per question.
holds() { [[ $'\n'$1$'\n' == *$'\n'"$2"$'\n'* ]]; }

# Every leaf command as "PROGRAM WORDS...", found by walking the help texts, and its help text.
commands=()
declare -A help_of
walk() {
  local help subs
  help=$("$@" --help)
  subs=$(subcommands_in "$help")
  if [[ -z $subs ]]; then
    commands+=("$(basename "$1") ${*:2}")
    help_of["${commands[-1]}"]=$help
    return
  fi
  local sub
  for sub in $subs; do walk "$@" "$sub"; done
}
walk "$vt"
walk "$vt_capture"

for command in "${commands[@]}"; do
  help=${help_of[$command]}
  section=$(section_of "$command")
  if [[ -z $section ]]; then
    fail "docs/commands.md has no section '## $command'"
    continue
  fi
  # The options the section's table lists: the first cell of each row, "`-o, --output`".
  listed=$(sed -n 's/^| `\([^`]*\)` |.*/\1/p' <<< "$section" | tr ',' '\n' | tr -d ' ')
  printed=$(options_in "$help")
  while read -r option; do
    [[ -z $option ]] && continue
    checked=$((checked + 1))
    holds "$listed" "$option" ||
      fail "'$command --help' prints $option, which the table of '## $command' in docs/commands.md lacks"
  done <<< "$printed"
  while read -r option; do
    [[ $option == -* ]] || continue  # a positional argument's row
    holds "$printed" "$option" ||
      fail "docs/commands.md lists $option under '## $command', which its --help does not print"
  done <<< "$listed"
done

# No section for a command that does not exist.
while read -r heading; do
  found=0
  for command in "${commands[@]}"; do [[ $heading == "$command" ]] && found=1; done
  ((found)) || fail "docs/commands.md has a section '## $heading', which is no subcommand"
done < <(sed -n 's/^## \(vt.*\)$/\1/p' "$doc")

if ((failures)); then
  echo "docs/commands.md disagrees with --help in $failures places (above): update docs/commands.md" >&2
  exit 1
fi
echo "PASS: docs/commands.md lists the ${#commands[@]} subcommands and the $checked options their --help prints"
