#!/usr/bin/env bash
# The second command of the README (and CI's): installs what is missing, builds in Release with
# warnings as errors and runs every test with ctest; then fuzzes every input parser for 30 s each
# (scripts/fuzz.sh), runs the threaded parts under ThreadSanitizer, and every test again
# built with AddressSanitizer + UndefinedBehaviorSanitizer.
#   --no-sanitizers   skip the fuzzing and sanitizer passes (quicker local runs)
set -euo pipefail
cd "$(dirname "$0")/.."

sanitizers=1
for arg in "$@"; do
  case "$arg" in
    --no-sanitizers) sanitizers=0 ;;
    *) echo "usage: scripts/test.sh [--no-sanitizers]" >&2; exit 2 ;;
  esac
done

jobs=$(nproc)
# Each step's wall time, printed at the end (also when a step fails): where the command's time goes.
step_times=()
timed() {  # label, command...
  local label=$1 began=$SECONDS
  shift
  "$@"
  step_times+=("$label $((SECONDS - began)) s")
}
print_step_times() {
  local IFS=';'
  ((${#step_times[@]})) && echo "test.sh steps: ${step_times[*]}; total $SECONDS s"
}
trap print_step_times EXIT
timed dependencies bash scripts/install-deps.sh
# The real Quake 3 map the retexturing tests use (q3dm6ish), from Debian's OpenArena packages.
began=$SECONDS
VT_OPENARENA_DIR=$(bash scripts/fetch-openarena.sh)
step_times+=("openarena $((SECONDS - began)) s")
export VT_OPENARENA_DIR

# llvmpipe's results depend on these (docs/design.md section 7): pin them for every test run.
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
export EGL_PLATFORM=surfaceless

# Unity builds: CMake compiles each target's sources 8 at a time as one translation unit. Most of
# the compile time goes to what every file parses and instantiates again (CLI11, nlohmann-json,
# gtest), and in the sanitizer builds to instrumenting it: batched, that is done once per batch.
# A batch holds files of one target only, so per-target flags (the oracle's -mfma) stay as they
# are; 8 files a batch leave enough batches to keep both cores busy to the end of each build.
unity=(-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8)

run_suite() {  # build folder, tests to leave out (a ctest regex, or ''), extra cmake arguments...
  local folder=$1 exclude=$2
  shift 2
  echo "== configure and build $folder"
  cmake -S . -B "$folder" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVT_WARNINGS_AS_ERRORS=ON \
    -DVT_BUILD_TESTS=ON -DVT_BUILD_BENCHMARKS=ON "${unity[@]}" "$@"
  timed "$folder-build" cmake --build "$folder" --parallel "$jobs"
  # ctest starts the longest tests first once it knows their times, which a new build folder does
  # not: with 2 cores, a 2-minute test started last leaves one core idle for 2 minutes. A folder
  # without times gets those of a clean-clone run of this pass (tests/ctest-costs/, ctest's own
  # file); ctest updates them after every run.
  local costs=$folder/Testing/Temporary/CTestCostData.txt seed=tests/ctest-costs/$folder.txt
  if [[ ! -f $costs && -f $seed ]]; then
    mkdir -p "${costs%/*}"
    cp "$seed" "$costs"
  fi
  echo "== test $folder"
  timed "$folder-tests" ctest --test-dir "$folder" --output-on-failure --parallel "$jobs" \
    --timeout 600 ${exclude:+-E "$exclude"}
}

run_suite build ''

# Left out of the sanitizer pass, to keep CI within its time: the tests that retexture and build
# q3dm6ish again for their own flights (one retexturing test of it stays), the SIGKILL tests
# (they check files, not memory), the demo, the chapter-4 miniature (retexturing and a 1 GB build
# again), the driver variants and all calibrations but llvmpipe's (each a calibration and
# crosschecks in processes of their own, whose code Calibration.Llvmpipe... and the crosscheck
# tests run under the sanitizers), the red+k captures of llvmpipe and of the H100 (the verdict's
# width, measured in the Release pass; the H100's runs the demo, whose GL driver's allocations
# LeakSanitizer cannot name, see tests/CMakeLists.txt) and the planted bugs (the verdict's power; the result
# sets they exercise run under the sanitizers in CrosscheckCommand.*Gl45Set), and the sharded
# crosscheck and evaluation run both ways (4.5 minutes of the H100's captures with every pixel's
# sets under ASan, and a demo whose GL driver's allocations LeakSanitizer cannot name; the merge and its records run under the sanitizers in Merge.* and
# GoldenShards.*, and fuzz_shard), the probe folders with one wrong value (a calibration each, 2.8
# minutes under ASan; the fit runs under the sanitizers in Calibration.Llvmpipe... and
# CalibrateProbes.ANonFinite...), and the checks of the text (docs, imports, function lengths),
# whose memory is bash's. Each runs in the Release pass above; the parsers they read with are
# fuzzed under AddressSanitizer.
# The sanitizer builds compile at -O1, as the sanitizers' documentation advises: the builds are
# most of CI's time, and -O1 keeps the stack traces readable.
sanitizer_optimization="-O1 -DNDEBUG"
sanitizer_exclude='^(Q3dm6ish|GoldenBackend\.TheGlPathPassesQ3dm6ish|CaptureCrosscheck\.Q3dm6ish|CrosscheckCommand\.Q3dm6ish|OpenArena/StoryboardPaths\.|OpenArenaMap\.OursWastes|CrashConsistency\.|DemoCommand\.|PlantedBugs\.|PlantedBugsOnAVariant\.|ArithmeticVariant\.|LlvmpipeVariant\.|Calibration\.(Softpipe|IsDeterministic)|CalibrateCommand\.|CaptureCrosscheck\.RedRaised|GpuEvidence\.RedRaised|Chapter4\.|VtCapture\.Probes|CrosscheckShards\.|EvalShards\.|CalibrateProbes\.OneWrongValue|Docs\.|ImportGraph\.|FunctionLength\.)'

if ((sanitizers)); then
  # libFuzzer on every input parser, 30 s each, two at a time (seeds from the Release vt above):
  # each run starts from the seeds again, and half a minute keeps twelve programs within six
  # minutes of the test command's 25. `bash scripts/fuzz.sh` alone fuzzes a minute each.
  VT_EXECUTABLE=build/src/vt VT_FUZZ_SECONDS=${VT_FUZZ_SECONDS:-30} \
    timed fuzzing bash scripts/fuzz.sh

  # ThreadSanitizer over the code that starts its own threads: the streaming thread, concurrent
  # page reads and writes, and the oracle's tile workers, which this build runs on std::thread
  # (VT_STD_THREAD_WORKERS, src/common/parallel_for.h). Code parallelised with TBB (the texture
  # builder, retexturing) is left out: TBB is not instrumented and its synchronisation reads as
  # races.
  echo "== configure and build build-tsan"
  cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=Release -DVT_WARNINGS_AS_ERRORS=ON \
    -DVT_SANITIZE_THREAD=ON -DVT_BUILD_BENCHMARKS=OFF "-DCMAKE_CXX_FLAGS_RELEASE=$sanitizer_optimization" \
    "${unity[@]}"
  timed build-tsan-build cmake --build build-tsan --parallel "$jobs" --target vt_thread_tests
  echo "== test build-tsan"
  TSAN_OPTIONS=halt_on_error=1 timed build-tsan-tests ctest --test-dir build-tsan \
    --output-on-failure --parallel "$jobs" --timeout 600 \
    -R '^(Runtime|PageCache|PageTable|VirtualTextureFile|Oracle|Stability|FrameComparison|NeedbufferScale)\.'

  # Leak checking stays on for our code (the GL tests turn it off: tests/CMakeLists.txt says why).
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  run_suite build-sanitize "$sanitizer_exclude" -DVT_SANITIZE=ON -DVT_BUILD_BENCHMARKS=OFF \
    "-DCMAKE_CXX_FLAGS_RELEASE=$sanitizer_optimization"
fi
