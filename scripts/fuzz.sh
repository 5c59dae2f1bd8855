#!/usr/bin/env bash
# Fuzzing (docs/hardening.md): builds the libFuzzer programs of tests/fuzz with clang in
# build-fuzz (-fsanitize=fuzzer,address,undefined), makes their seed corpora from real files
# (scripts/fuzz-seeds.py: OpenArena's q3dm6ish and what `vt retexture` and `vt build` make of
# it, and the models, probes and configurations under data/), runs every program for
# VT_FUZZ_SECONDS (60) seconds, two at a time, and prints for each the executions and the
# coverage libFuzzer reached. Fails on any crash, hang, out-of-memory, leak or sanitizer report;
# the input that caused it stays in the build folder's crashes/<target>/, to be kept as
# tests/fuzz/regressions/<target>/<name> once the parser is fixed.
#   scripts/fuzz.sh [TARGET...]          (default: every target of tests/fuzz/CMakeLists.txt)
# Needs the Release `vt` (VT_EXECUTABLE, default build/src/vt) for the seeds. VT_FUZZ_BUILD_DIR
# names a build folder configured already with -DVT_FUZZ=ON (scripts/test.sh's sanitizer build,
# which builds the programs beside the tests) instead of build-fuzz.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${VT_FUZZ_SECONDS:-60}
parallel=${VT_FUZZ_PARALLEL:-2}
vt=${VT_EXECUTABLE:-build/src/vt}
folder=${VT_FUZZ_BUILD_DIR:-build-fuzz}
all_targets=(vt_file bsp pk3 obj layout camera_path needbuffer capture precision_model probe_folder
  config shard)
targets=("${@:-${all_targets[@]}}")
[[ -x "$vt" ]] || { echo "fuzz: $vt is missing: build the Release vt first" >&2; exit 1; }
openarena=${VT_OPENARENA_DIR:-$(bash scripts/fetch-openarena.sh)}

start=$SECONDS
echo "== configure and build $folder (clang, libFuzzer, ASan, UBSan)"
mkdir -p "$folder"
if [[ -z ${VT_FUZZ_BUILD_DIR:-} ]]; then
  # A unity build, as scripts/test.sh's (which says why), at -O1 as libFuzzer's documentation
  # advises for its programs: it compiles faster, and most of the fuzzing time is the sanitizers'.
  cmake -S . -B "$folder" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
    "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" \
    -DVT_FUZZ=ON -DVT_BUILD_TESTS=OFF -DVT_BUILD_BENCHMARKS=OFF -DCMAKE_UNITY_BUILD=ON \
    -DCMAKE_UNITY_BUILD_BATCH_SIZE=8 >"$folder/configure.log" 2>&1 ||
    { cat "$folder/configure.log"; exit 1; }
fi
cmake --build "$folder" --parallel "$(nproc)" --target "${targets[@]/#/fuzz_}"
built=$SECONDS

echo "== seed corpora"
seeds=$folder/seeds
rm -rf "$seeds" "$folder/inputs"
mkdir -p "$folder/inputs/textures"
"$vt" retexture q3dm6ish --packages "$openarena" -o "$folder/inputs/q3" --no-coherence >/dev/null
textures=$folder/inputs/textures
oiiotool --pattern checker:width=8:height=8 64x64 3 -o "$textures/checker.png"
oiiotool --pattern fill:top=0.2,0.4,0.9:bottom=0.9,0.5,0.1 40x24 4 -o "$textures/gradient.png"
cat >"$textures/sparse.json" <<'EOF'
{"page_size": 16, "border": 2, "side": 128, "channels": 4, "filter": "tent",
 "color_space": "linear", "background": [0, 0, 0, 255],
 "images": [{"file": "checker.png", "x": 0, "y": 0},
            {"file": "gradient.png", "x": 96, "y": 80, "width": 30, "height": 40,
             "source_x": -7, "source_y": 5}]}
EOF
"$vt" build "$textures/checker.png" -o "$textures/checker.vt" --page-size 16 --border 1 -q >/dev/null
"$vt" build "$textures/sparse.json" -o "$textures/sparse.vt" -q >/dev/null
# The block formats' pages (bc1 dense, bc3 sparse with alpha), which the vt_file target decodes.
"$vt" build "$textures/checker.png" -o "$textures/checker-bc1.vt" --page-size 16 --border 2 \
  --format bc1 -q >/dev/null
"$vt" build "$textures/sparse.json" -o "$textures/sparse-bc3.vt" --format bc3 -q >/dev/null
# Version 3: the ancestor errors after the pages.
"$vt" build "$textures/sparse.json" -o "$textures/sparse-errors.vt" --ancestor-errors -q >/dev/null
python3 scripts/fuzz-seeds.py "$openarena" "$folder/inputs/q3" "$textures" "$seeds"
# The stored regression inputs seed their targets too.
for target in "${targets[@]}"; do
  if [[ -d tests/fuzz/regressions/$target ]]; then
    mkdir -p "$seeds/$target"
    cp tests/fuzz/regressions/"$target"/* "$seeds/$target/"
  fi
done

echo "== fuzz ${#targets[@]} targets for $seconds s each, $parallel at a time"
logs=$folder/logs
rm -rf "$logs" "$folder/corpus" "$folder/crashes"
mkdir -p "$logs"
# A hang is an input that runs over 20 s; an allocation over 2 GiB is an out-of-memory.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fuzz_one() {
  local target=$1
  mkdir -p "$folder/corpus/$target" "$folder/crashes/$target"
  local rc=0
  "$folder/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$folder/crashes/$target/" \
    "$folder/corpus/$target" "$seeds/$target" >"$logs/$target.log" 2>&1 || rc=$?
  echo "$rc" >"$logs/$target.rc"
}
for target in "${targets[@]}"; do
  while (($(jobs -rp | wc -l) >= parallel)); do wait -n || true; done
  fuzz_one "$target" &
done
wait

failed=0
printf '%-16s %12s %10s %8s %8s %8s  %s\n' target executions exec/s cov ft corpus result
for target in "${targets[@]}"; do
  log=$logs/$target.log
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  final=$(grep -E '^#[0-9]+[[:space:]]+(DONE|pulse|NEW|REDUCE|INITED)' "$log" | tail -1 || true)
  field() { sed -n "s/.* $1: *\([0-9a-zA-Z/]*\).*/\1/p" <<<"$final"; }
  rate=$((${executions:-0} / seconds))
  result=passed
  if [[ $(cat "$logs/$target.rc") != 0 ]]; then
    result="FAILED: $(ls "$folder/crashes/$target" | head -1) (log $log)"
    failed=1
  fi
  printf '%-16s %12s %10s %8s %8s %8s  %s\n' "$target" "${executions:-?}" "$rate" \
    "$(field cov)" "$(field ft)" "$(ls "$folder/corpus/$target" | wc -l)" "$result"
done
echo "fuzz: build $((built - start)) s, seeds and runs $((SECONDS - built)) s"
if ((failed)); then
  echo "fuzz: a target failed; its input is in $folder/crashes/<target>/ (the log shows the report)" >&2
  for target in "${targets[@]}"; do
    [[ $(cat "$logs/$target.rc") == 0 ]] || tail -40 "$logs/$target.log" >&2
  done
  exit 1
fi
