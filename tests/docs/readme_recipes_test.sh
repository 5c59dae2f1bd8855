#!/usr/bin/env bash
# README.md's recipes do what it shows: every command block of "## Recipes" that runs on a CPU is
# run verbatim, in order, after the demo (`vt demo --output out/demo`, the job of
# `scripts/demo.sh`, whose last lines the first recipe shows), in a scratch root that holds
# build/src (this build's programs), scripts/ and data/; each line of the output the README prints
# after a block must be one the block printed. In a shown line "..." stands for any text, a time in
# ms for any time, and the llvmpipe and Mesa versions for any version. Not run here: the GPU kit
# (tests/gpu_kit/gpu_kit_test.sh runs it on llvmpipe) and the full chapter-4 reproduction (20
# minutes; its miniature is Chapter4.MiniatureReport). Skipped (exit 77) where $VT_OPENARENA_DIR is
# unset: the golden recipe retextures q3dm6ish.
#   tests/docs/readme_recipes_test.sh SOURCE BUILD WORK
set -euo pipefail
source=$1 build=$2 work=$3
if [[ -z ${VT_OPENARENA_DIR:-} ]]; then
  echo "skipped: VT_OPENARENA_DIR is not set (the golden recipe needs OpenArena)"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work/build"
ln -s "$build/src" "$work/build/src"
ln -s "$source/scripts" "$work/scripts"
ln -s "$source/data" "$work/data"
export LP_NUM_THREADS=2 EGL_PLATFORM=surfaceless
cd "$work"
python3 - "$source/README.md" <<'PYTHON'
import re, subprocess, sys

lines = open(sys.argv[1], encoding="utf-8").read().split("\n")
start = lines.index("## Recipes")
end = next(i for i in range(start + 1, len(lines)) if lines[i].startswith("## "))

# (heading, code, shown output or None) for every ```sh block of the recipes.
blocks, heading, i = [], "", start
while i < end:
    if lines[i].startswith("### "):
        heading = lines[i][4:]
    if lines[i] == "```sh":
        j = lines.index("```", i + 1)
        code = "\n".join(lines[i + 1:j])
        shown, k = None, j + 1
        while k < end and not lines[k].startswith("### ") and lines[k] != "```sh":
            if lines[k] == "```":
                shown = lines[k + 1:lines.index("```", k + 1)]
                break
            k += 1
        blocks.append((heading, code, shown))
        i = j
    i += 1

def normal(line):
    line = re.sub(r"[0-9]+\.[0-9]+ ms", "T ms", line)
    line = re.sub(r"LLVM [0-9.]+, [0-9]+ bits", "LLVM V", line)
    return re.sub(r"Mesa [0-9][0-9.]*", "Mesa V", line)

def printed(shown, output):
    """Whether the shown line is a line of the output ("..." stands for any text)."""
    want = normal(shown)
    parts = want.split("...")
    for line in map(normal, output.split("\n")):
        if len(parts) == 1:
            if line == want:
                return True
            continue
        head, tail = parts[0], parts[-1]
        if len(line) < len(head) + len(tail) or not (line.startswith(head) and line.endswith(tail)):
            continue
        at, ok = len(head), True
        for middle in parts[1:-1]:
            at = line.find(middle, at)
            if at < 0 or at + len(middle) > len(line) - len(tail):
                ok = False
                break
            at += len(middle)
        if ok:
            return True
    return False

failures, ran = 0, 0
for heading, code, shown in blocks:
    if "scripts/gpu-kit.sh" in code or "reproduce-chapter4.sh" in code:
        print(f"not run here: {heading}: {code.splitlines()[0]}")
        continue
    if code == "bash scripts/demo.sh":
        code = "build/src/vt demo --output out/demo"  # the demo's job without the packages
    result = subprocess.run(["bash", "-euo", "pipefail", "-c", code], capture_output=True,
                            text=True)
    ran += 1
    output = result.stdout + result.stderr
    if result.returncode != 0:
        print(f"FAIL: {heading}: exit {result.returncode}\n{code}\n{output[-2000:]}")
        failures += 1
        continue
    for line in shown or []:
        if line.strip() == "" or line.strip().startswith("..."):
            continue
        if not printed(line, output):
            print(f"FAIL: {heading}: the README shows a line the recipe did not print:\n  {line}"
                  f"\nit printed:\n{output[-3000:]}")
            failures += 1
    print(f"ran: {heading}: {code.splitlines()[0]}")
print(f"README recipes: {ran} run, {failures} failures")
sys.exit(1 if failures or ran == 0 else 0)
PYTHON
rm -f "$work/out/q3dm6ish.vt"  # 1 GB; the rest stays for a look
