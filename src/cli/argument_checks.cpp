#include "cli/argument_checks.h"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "common/shard.h"
#include "runtime/heuristic.h"

namespace vt {
namespace {

// "a,b,c" -> each item; an empty item is kept (and refused by the item's check).
std::vector<std::string> items(const std::string& text) {
  std::vector<std::string> result;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) result.push_back(item);
  if (text.empty() || text.back() == ',') result.emplace_back();
  return result;
}

// The whole of `text` as a number, or nothing (strtoll and strtod accept a prefix).
bool wholeNumber(const std::string& text, long long& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(text.c_str(), &end, 10);
  return errno == 0 && *end == '\0';
}

}  // namespace

CLI::Validator workerCount() {
  return wholeNumbersIn(0, kMaxWorkerThreads).name("0.." + std::to_string(kMaxWorkerThreads));
}

CLI::Validator pageSizeArgument() {
  return validatorFrom(
      [](const std::string& text) {
        long long size = 0;
        if (!wholeNumber(text, size) || size < 1 || size > 4096 ||
            std::popcount(static_cast<unsigned long long>(size)) != 1)
          throw std::invalid_argument("page size '" + text +
                                      "' is not a power of two in [1, 4096]");
      },
      "POWER_OF_TWO");
}

CLI::Validator textureSideArgument() {
  return validatorFrom(
      [](const std::string& text) {
        long long side = 0;
        if (!wholeNumber(text, side) || side < 1 || side > (4096LL << 15) ||
            std::popcount(static_cast<unsigned long long>(side)) != 1)
          throw std::invalid_argument("side '" + text +
                                      "' is not a power of two in [1, 2^27] (page size times "
                                      "2^L, L <= 15)");
      },
      "POWER_OF_TWO");
}

CLI::Validator heuristicArgument(bool list) {
  return validatorFrom(
      [list](const std::string& text) {
        for (const std::string& heuristic : list ? items(text) : std::vector{text})
          Heuristic::parse(heuristic);
      },
      "HEURISTIC");
}

CLI::Validator finiteNumber() {
  return validatorFrom(
      [](const std::string& text) {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(value))
          throw std::invalid_argument("'" + text + "' is not a finite number");
      },
      "NUMBER");
}

CLI::Validator wholeNumbersIn(long long low, long long high) {
  return validatorFrom(
      [low, high](const std::string& text) {
        for (const std::string& item : items(text)) {
          long long value = 0;
          if (!wholeNumber(item, value) || value < low || value > high)
            throw std::invalid_argument("'" + item + "' is not a whole number from " +
                                        std::to_string(low) + " to " + std::to_string(high));
        }
      },
      "INT");
}

CLI::Validator shardArgument() {
  return validatorFrom([](const std::string& text) { parseShard(text); }, "I/N");
}

}  // namespace vt
