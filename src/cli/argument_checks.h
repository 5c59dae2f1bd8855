#pragma once
// CLI11 validators for the arguments that have a range or a grammar, so that a bad value is a bad
// argument everywhere (the error, the command's usage line, exit code 2) and never reaches the
// library, where it would be blamed on an input file or ask for memory.

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

namespace vt {

// Worker threads and parallel jobs: 0 (every core) to kMaxWorkerThreads.
inline constexpr unsigned kMaxWorkerThreads = 1024;
CLI::Validator workerCount();

// A page size: a power of two in [1, 4096] (the file format's range).
CLI::Validator pageSizeArgument();

// A texture's finest side: a power of two up to the largest page size times 2^15 (the format's
// limits); whether it fits the page size is checked once that is known.
CLI::Validator textureSideArgument();

// A page-priority heuristic ("pixelsum*distance"), or with `list` a comma-separated list of them.
CLI::Validator heuristicArgument(bool list = false);

// A finite number (no nan, no inf).
CLI::Validator finiteNumber();

// A comma-separated list of whole numbers in [low, high].
CLI::Validator wholeNumbersIn(long long low, long long high);

// A shard of the work, I/N (common/shard.h).
CLI::Validator shardArgument();

// A validator that reports the std::invalid_argument of `parse(text)` as CLI11's error text.
template <class Parse>
CLI::Validator validatorFrom(Parse parse, const char* name) {
  return CLI::Validator(
      [parse](std::string& text) {
        try {
          parse(text);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      },
      name);
}

}  // namespace vt
