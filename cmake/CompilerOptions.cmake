# Warnings, IEEE floating point and sanitizers for every target of the project.
#
# The oracle's numbers depend on IEEE arithmetic in the order the source states it, so no fast
# math option ever, and no contraction of a*b+c into fma behind the source's back: where a fused
# multiply-add is meant, the code calls std::fma.
add_library(vt_compile_options INTERFACE)
target_compile_options(vt_compile_options INTERFACE -Wall -Wextra -Wpedantic -ffp-contract=off)
if(VT_WARNINGS_AS_ERRORS)
  target_compile_options(vt_compile_options INTERFACE -Werror)
endif()
# Unity builds (CMAKE_UNITY_BUILD, scripts/test.sh) compile each .cpp as an included file, and GCC
# then takes a class that holds a type from the file's anonymous namespace (a pimpl's state) for
# one that a header could define twice. One .cpp file defines it once, as in the normal build.
if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(vt_compile_options INTERFACE -Wno-subobject-linkage)
endif()
option(VT_SANITIZE_THREAD "Build with ThreadSanitizer" OFF)
if(VT_SANITIZE_THREAD)
  target_compile_options(vt_compile_options INTERFACE -fsanitize=thread -fno-omit-frame-pointer)
  target_link_options(vt_compile_options INTERFACE -fsanitize=thread)
endif()
# The oracle's tile workers on std::thread instead of TBB (reference/parallel_for.h), so that
# ThreadSanitizer, which cannot see into TBB, checks them. Same bytes either way.
option(VT_STD_THREAD_WORKERS "Run the oracle's parallel loops on std::thread instead of TBB"
       ${VT_SANITIZE_THREAD})
if(VT_STD_THREAD_WORKERS)
  target_compile_definitions(vt_compile_options INTERFACE VT_STD_THREAD_WORKERS)
endif()
if(VT_SANITIZE)
  target_compile_options(vt_compile_options INTERFACE -fsanitize=address,undefined
                                                      -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(vt_compile_options INTERFACE -fsanitize=address,undefined)
endif()
# The fuzz programs of tests/fuzz (scripts/fuzz.sh): every library built with AddressSanitizer and
# UndefinedBehaviorSanitizer, and those the programs read their inputs with (target property
# VT_FUZZ_COVERAGE, tests/fuzz/CMakeLists.txt) instrumented for libFuzzer's coverage too;
# libFuzzer itself comes with clang. With VT_SANITIZE as well, one build serves the sanitizer tests
# and the fuzzing (scripts/test.sh): the coverage instrumentation changes no result, and leaving
# out the oracle's rasterization and shading, the command line and the tests keeps the sanitizer
# tests' time near a build's without it (226 s against 180 s; 305 s with it everywhere:
# docs/benchmarks.md).
option(VT_FUZZ "Build the libFuzzer programs of tests/fuzz (clang only)" OFF)
if(VT_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "VT_FUZZ needs clang: configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  target_compile_options(vt_compile_options INTERFACE -gline-tables-only
    $<$<BOOL:$<TARGET_PROPERTY:VT_FUZZ_COVERAGE>>:-fsanitize=fuzzer-no-link>)
  if(NOT VT_SANITIZE)
    target_compile_options(vt_compile_options INTERFACE -fsanitize=address,undefined
                           -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(vt_compile_options INTERFACE -fsanitize=address,undefined)
  endif()
endif()

# Fused multiply-add instructions for the oracle's hot code when the build machine has them: its
# std::fma calls become single instructions instead of calls into libm. Results are identical
# (fma is exact either way, and contraction stays off); only speed changes. A binary built so runs
# only on CPUs with FMA, so this follows the machine that builds it.
include(CheckCXXSourceRuns)
set(CMAKE_REQUIRED_FLAGS -mfma)
check_cxx_source_runs("int main() { return __builtin_cpu_supports(\"fma\") ? 0 : 1; }" VT_HOST_HAS_FMA)
unset(CMAKE_REQUIRED_FLAGS)
option(VT_USE_FMA_INSTRUCTIONS "Compile the oracle with -mfma (default: when this machine has FMA)"
       ${VT_HOST_HAS_FMA})
