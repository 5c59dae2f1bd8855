#!/usr/bin/env bash
# Every test README.md and docs/*.md cite by name (`Suite.Name`, or `Suite.Prefix...` for the
# tests whose names begin so) is one the tests define: TEST, TEST_F or TEST_P in tests/, or
# add_test(NAME ...) in tests/CMakeLists.txt. A test renamed or merged leaves no stale citation.
#   tests/docs/cited_tests_test.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
cd "$source_dir"
python3 - README.md docs/*.md <<'PYTHON'
import glob, re, sys

defined = set()
for path in glob.glob("tests/**/*.cpp", recursive=True):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for suite, name in re.findall(r"\bTEST(?:_F|_P)?\(\s*(\w+)\s*,\s*(\w+)\s*\)", text):
        defined.add(f"{suite}.{name}")
with open("tests/CMakeLists.txt", encoding="utf-8") as f:
    defined.update(re.findall(r"add_test\(NAME\s+([\w.]+)", f.read()))
suites = {name.split(".")[0] for name in defined}

failures = []
cited = 0
for page in sys.argv[1:]:
    with open(page, encoding="utf-8") as f:
        text = f.read()
    for suite, name, prefix in re.findall(r"`([A-Z]\w*)\.([A-Z]\w*)(\.\.\.)?`", text):
        if suite not in suites:
            continue  # not a test suite (a type's member, a file)
        cited += 1
        full = f"{suite}.{name}"
        found = any(d.startswith(full) for d in defined) if prefix else full in defined
        if not found:
            failures.append(f"{page}: `{full}{prefix}` names no test of tests/")
for failure in failures:
    print("FAIL:", failure, file=sys.stderr)
if failures:
    sys.exit(1)
print(f"PASS: {cited} tests cited by {len(sys.argv) - 1} pages are defined")
PYTHON
