#pragma once
// How `vt crosscheck` reports comparisons with the oracle (<vt/oracle/compare.h>), for rendered
// scenes and for captures alike: one printed line and one JSON record per frame, difference
// images, and the totals.

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "vt/oracle/compare.h"

namespace vt {

struct ComparisonTotals {
  uint64_t pixels = 0, identical = 0, explained = 0, unexplained = 0, ambiguous = 0;
  std::array<uint64_t, oracle::kReasons> explainedBy{}, unexplainedBy{};
  std::array<double, oracle::kReasons> widenBy{};

  void add(const oracle::Comparison& c);
  double ambiguousFraction() const;
  nlohmann::json json() const;
  // "<identical> of <pixels> pixels identical, <explained> explained, <unexplained> unexplained;
  // ambiguous fraction <f>"
  std::string line() const;
};

// The counts, by reason, the needbuffer mismatches and the colour differences.
nlohmann::json comparisonJson(const oracle::Comparison& c);

// "  <name> <detail> <pixels> pixels: ... identical, ... explained, ... unexplained, ambiguous
// ...; colour max M, mean D", then one line per parameter that would have to widen.
void printComparison(const std::string& name, const std::string& detail,
                     const oracle::Comparison& c);

// <stem>-color-difference.png and <stem>-classes.png in `folder`.
void writeComparisonImages(const std::filesystem::path& folder, const std::string& stem,
                           oracle::Viewport viewport, const oracle::Comparison& c);

}  // namespace vt
