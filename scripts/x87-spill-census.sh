#!/usr/bin/env bash
# Why GALLIUM_NOSSE=1 is bounded, not pinned (docs/precision-models.md): counts, in the machine
# code llvmpipe's JIT generates for one crosscheck scene under GALLIUM_NOSSE=1, where x87
# registers (64-bit significands) are stored to the stack as 32-bit floats. Each such store
# rounds an intermediate value to float; the others stay extended. Which values the register
# allocator spills is a property of the compiled shader and the compiler, not of an arithmetic
# choice, so no family member stated in general terms reproduces it.
#
#   scripts/x87-spill-census.sh TEXTURE.vt [SCENE]     (needs gdb and objdump; build/src/vt)
# Prints one line per executable region the JIT left mapped, then the totals.
set -euo pipefail
cd "$(dirname "$0")/.."
texture=${1:?usage: scripts/x87-spill-census.sh TEXTURE.vt [SCENE]}
scene=${2:-room}
[[ -f $texture ]] || { echo "$texture: no such file" >&2; exit 1; }
for tool in gdb objdump; do
  command -v "$tool" >/dev/null || { echo "x87-spill-census: $tool is not installed" >&2; exit 1; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/dump.py" <<'PY'
import gdb, os
class DumpJit(gdb.Command):
    def __init__(self): super().__init__("dump-jit", gdb.COMMAND_USER)
    def invoke(self, argument, from_tty):
        pid = gdb.selected_inferior().pid
        for line in open("/proc/%d/maps" % pid):
            fields = line.split()
            if "x" in fields[1] and len(fields) < 6:  # executable and anonymous: JIT code
                start, end = fields[0].split("-")
                gdb.execute("dump memory %s/region_%s.bin 0x%s 0x%s"
                            % (os.environ["CENSUS_DIR"], start, start, end))
DumpJit()
PY

CENSUS_DIR=$work GALLIUM_NOSSE=1 LP_NUM_THREADS=${LP_NUM_THREADS:-2} \
  EGL_PLATFORM=${EGL_PLATFORM:-surfaceless} \
  gdb -batch -ex 'set breakpoint pending on' -ex "source $work/dump.py" \
  -ex 'break eglDestroyContext' -ex run -ex dump-jit -ex kill \
  --args ./build/src/vt crosscheck "$texture" --scenes "$scene" --model gl45 -o "$work/crosscheck" \
  > "$work/gdb.log" 2>&1 || { tail -5 "$work/gdb.log" >&2; exit 1; }

total_spills=0 total_reloads=0 total_sse=0
shopt -s nullglob
for region in "$work"/region_*.bin; do
  objdump -D -b binary -m i386:x86-64 -M intel "$region" > "$region.s"
  spills=$(grep -cE 'fstp? +DWORD PTR \[rsp' "$region.s" || true)
  reloads=$(grep -cE 'fld +DWORD PTR \[rsp' "$region.s" || true)
  sse=$(grep -cE '\b[xy]mm[0-9]' "$region.s" || true)
  instructions=$(grep -cE '^ +[0-9a-f]+:' "$region.s" || true)
  echo "$(basename "$region" .bin): $instructions instructions, $spills float stores of x87" \
    "registers to the stack, $reloads float loads from it, $sse using SSE registers"
  total_spills=$((total_spills + spills)) total_reloads=$((total_reloads + reloads))
  total_sse=$((total_sse + sse))
done
echo "total: $total_spills x87 values rounded to float on the stack, $total_reloads reloaded," \
  "$total_sse instructions on SSE registers"
