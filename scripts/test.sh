#!/usr/bin/env bash
# The second command of the README (and CI's): installs what is missing, builds in Release with
# warnings as errors, and runs every test once with ctest: most built with AddressSanitizer +
# UndefinedBehaviorSanitizer, those tests/release-only.txt names in the Release build. Between the
# two it runs the threaded parts under ThreadSanitizer and fuzzes every input parser for 20 s each
# (scripts/fuzz.sh) with the sanitizer build's libFuzzer programs.
#   --no-sanitizers   every test in the Release build; no fuzzing and no sanitizer pass
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

build_suite() {  # build folder, extra cmake arguments...
  local folder=$1
  shift
  echo "== configure and build $folder"
  cmake -S . -B "$folder" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVT_WARNINGS_AS_ERRORS=ON \
    -DVT_BUILD_TESTS=ON "${unity[@]}" "$@"
  timed "$folder-build" cmake --build "$folder" --parallel "$jobs"
}

test_suite() {  # build folder, ctest arguments choosing the tests...
  local folder=$1
  shift
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
    --timeout 600 "$@"
}

build_suite build -DVT_BUILD_BENCHMARKS=ON
if ((!sanitizers)); then
  test_suite build
  exit 0
fi

# With the sanitizers, every test runs once: those tests/release-only.txt names (it says why) in
# the Release build, every other one in the sanitizer build at the end.
mapfile -t release_only < <(sed -e 's/#.*//' -e 's/[[:space:]]*$//' tests/release-only.txt |
  grep -v '^$')
# A build folder's test names (a parameterised test's listed name ends in its parameter's bytes,
# which differ between builds: left out).
test_names() {
  ctest --test-dir "$1" -N | sed -n -e 's/  # GetParam() = .*//' -e 's/^ *Test *#[0-9]*: //p'
}
tests=$(test_names build)
for pattern in "${release_only[@]}"; do
  grep -Eq "^($pattern)" <<<"$tests" ||
    { echo "tests/release-only.txt: '$pattern' matches no test" >&2; exit 1; }
done
release_only_regex="^($(IFS='|'; echo "${release_only[*]}"))"
test_suite build -R "$release_only_regex"

# The sanitizer builds compile at -O1, as the sanitizers' documentation advises: the builds are
# most of CI's time, and -O1 keeps the stack traces readable.
sanitizer_optimization="-O1 -DNDEBUG"

# ThreadSanitizer over the code that starts its own threads: the streaming thread, concurrent
# page reads and writes, and the oracle's tile workers, which this build runs on std::thread
# (VT_STD_THREAD_WORKERS, src/common/parallel_for.h). Code parallelised with TBB (the texture
# builder, retexturing) is left out: TBB is not instrumented and its synchronisation reads as
# races. These tests run in one of the other passes too.
echo "== configure and build build-tsan"
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=Release -DVT_WARNINGS_AS_ERRORS=ON \
  -DVT_SANITIZE_THREAD=ON -DVT_BUILD_BENCHMARKS=OFF "-DCMAKE_CXX_FLAGS_RELEASE=$sanitizer_optimization" \
  "${unity[@]}"
timed build-tsan-build cmake --build build-tsan --parallel "$jobs" --target vt_thread_tests
echo "== test build-tsan"
TSAN_OPTIONS=halt_on_error=1 timed build-tsan-tests ctest --test-dir build-tsan \
  --output-on-failure --parallel "$jobs" --timeout 600 \
  -R '^(Runtime|PageCache|PageTable|VirtualTextureFile|Oracle|Stability|FrameComparison|NeedbufferScale)\.'

# AddressSanitizer + UndefinedBehaviorSanitizer, built with clang: it compiled this project's
# instrumented sources in half GCC's time (docs/benchmarks.md), and a second compiler's reading of
# the code is a check of its own (it found arguments whose order of evaluation C++ leaves open,
# common/random_draws.h). Leak checking stays on for our code (the GL tests turn it off:
# tests/CMakeLists.txt says why).
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The same build holds the libFuzzer programs (-DVT_FUZZ=ON: the programs and the libraries that
# read their inputs also compiled with libFuzzer's coverage counters, which change no result), so
# that the fuzzing needs no build of its own.
build_suite build-sanitize -DCMAKE_CXX_COMPILER=clang++ -DVT_SANITIZE=ON -DVT_FUZZ=ON \
  -DVT_BUILD_BENCHMARKS=OFF "-DCMAKE_CXX_FLAGS_RELEASE=$sanitizer_optimization"
# Every test runs in one of the two passes: a Release test that tests/release-only.txt does not
# name must be one the sanitizer build defines.
missing=$(comm -23 <(grep -Ev "$release_only_regex" <<<"$tests" | sort) \
  <(test_names build-sanitize | sort))
if [[ -n $missing ]]; then
  echo "tests in neither pass (name them in tests/release-only.txt): $missing" >&2
  exit 1
fi

# libFuzzer on every input parser, 20 s each, two at a time (seeds from the Release vt): each run
# starts from the seeds again, and a third of a minute keeps twelve programs within two minutes of
# the test command's 25. `bash scripts/fuzz.sh` alone fuzzes a minute each.
VT_EXECUTABLE=build/src/vt VT_FUZZ_BUILD_DIR=build-sanitize VT_FUZZ_SECONDS=${VT_FUZZ_SECONDS:-20} \
  timed fuzzing bash scripts/fuzz.sh

test_suite build-sanitize -E "$release_only_regex"
