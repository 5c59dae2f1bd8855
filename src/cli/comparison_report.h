#pragma once
// How `vt crosscheck` reports comparisons with the oracle (<vt/oracle/compare.h>), for rendered
// scenes and for captures alike: one printed line and one JSON record per frame, difference
// images, and the totals.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "vt/oracle/compare.h"

namespace vt {

struct ComparisonTotals {
  uint64_t pixels = 0, identical = 0, flagged = 0, withinBound = 0, mismatched = 0;

  void add(const oracle::Comparison& c);
  nlohmann::json json() const;
  // "<identical> of <pixels> pixels identical, <flagged> flagged, ... mismatched"
  std::string line() const;
};

// The counts, the needbuffer mismatches and the colour differences.
nlohmann::json comparisonJson(const oracle::Comparison& c);

// "  <name> <detail> <pixels> pixels: ... identical, ... flagged, ...; colour max M, mean D"
void printComparison(const std::string& name, const std::string& detail,
                     const oracle::Comparison& c);

// <stem>-color-difference.png and <stem>-classes.png in `folder`.
void writeComparisonImages(const std::filesystem::path& folder, const std::string& stem,
                           oracle::Viewport viewport, const oracle::Comparison& c);

}  // namespace vt
