#pragma once
// How `vt crosscheck` reports comparisons with the oracle (<vt/oracle/compare.h>), for rendered
// scenes and for captures alike: one printed line and one JSON record per frame, difference
// images, and the totals. Beside the ambiguous fraction each reports how tight the verdict is: the
// mean colour width, candidate levels and candidate pages of the covered pixels' result sets
// (SetWidths, src/render/frame_comparison.h, defines them). Both count the pixels whose sets were
// built: every pixel, or, with sets built against the compared frame (the default of `vt
// crosscheck`, oracle::RenderOptions' judged frame), the pixels where it differs.

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "render/frame_comparison.h"
#include "vt/oracle/compare.h"

namespace vt {

struct ComparisonTotals {
  uint64_t pixels = 0, identical = 0, explained = 0, unexplained = 0, ambiguous = 0;
  uint64_t setPixels = 0;  // those the ambiguous fraction and the widths count
  bool judged = false;     // some frame's sets were built where it differs only
  std::array<uint64_t, oracle::kReasons> explainedBy{}, unexplainedBy{};
  std::array<double, oracle::kReasons> widenBy{};
  SetWidths widths;

  void add(const oracle::Comparison& c, const SetWidths& frameWidths);
  // Another run's totals added, as if its frames had been added here one by one after these
  // (every sum of doubles is the same sum in the same order when `other` holds one frame).
  void add(const ComparisonTotals& other);
  double ambiguousFraction() const;
  // Every count and sum as it is, for a shard's record (common/shard.h); fromRecord reads it back
  // exactly (doubles are written with 17 digits) and throws nlohmann::json::exception when
  // malformed.
  nlohmann::json record() const;
  static ComparisonTotals fromRecord(const nlohmann::json& record);
  nlohmann::json json() const;
  // "<identical> of <pixels> pixels identical, <explained> explained, <unexplained> unexplained;
  // ambiguous fraction <f>, colour width <w>/255, <l> levels, <p> pages", the four followed by
  // "(of the differing pixels)" where they count those alone
  std::string line() const;
};

// The pixels whose sets the ambiguous count and the widths cover: every pixel, or where the sets
// were built against the compared frame, those that are not identical.
uint64_t setPixels(const oracle::Comparison& c);

// The counts, by reason, the needbuffer mismatches, the colour differences and the set widths.
nlohmann::json comparisonJson(const oracle::Comparison& c, const SetWidths& widths);

// "  <name> <detail> <pixels> pixels: ... identical, ... explained, ... unexplained, ambiguous
// ... (width W/255, L levels, P pages); colour max M, mean D", then one line per parameter that
// would have to widen.
void printComparison(const std::string& name, const std::string& detail,
                     const oracle::Comparison& c, const SetWidths& widths);

// The set widths as JUnit-style (name, value) properties, the ambiguous fraction among them.
std::vector<std::pair<std::string, std::string>> widthProperties(
    const oracle::Comparison& c, const SetWidths& widths);

// <stem>-color-difference.png and <stem>-classes.png in `folder`, compressed fast (written frame
// after frame).
void writeComparisonImages(const std::filesystem::path& folder, const std::string& stem,
                           oracle::Viewport viewport, const oracle::Comparison& c);

}  // namespace vt
