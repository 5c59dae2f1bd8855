#include "cli/comparison_report.h"

#include <cstdio>

#include "common/image_file.h"

namespace vt {

void ComparisonTotals::add(const oracle::Comparison& c) {
  pixels += c.pixels;
  identical += c.identical;
  flagged += c.flagged;
  withinBound += c.withinBound;
  mismatched += c.mismatched;
}

nlohmann::json ComparisonTotals::json() const {
  return {{"pixels", pixels},
          {"identical", identical},
          {"flagged", flagged},
          {"within_bound", withinBound},
          {"mismatched", mismatched}};
}

std::string ComparisonTotals::line() const {
  char text[200];
  std::snprintf(text, sizeof text,
                "%llu of %llu pixels identical, %llu flagged, %llu within bound, %llu mismatched",
                static_cast<unsigned long long>(identical), static_cast<unsigned long long>(pixels),
                static_cast<unsigned long long>(flagged),
                static_cast<unsigned long long>(withinBound),
                static_cast<unsigned long long>(mismatched));
  return text;
}

nlohmann::json comparisonJson(const oracle::Comparison& c) {
  return {{"pixels", c.pixels},
          {"identical", c.identical},
          {"flagged", c.flagged},
          {"within_bound", c.withinBound},
          {"mismatched", c.mismatched},
          {"needbuffer_mismatched", c.needMismatched},
          {"max_color_difference", c.maxColorDifference},
          {"mean_color_difference", c.meanColorDifference}};
}

void printComparison(const std::string& name, const std::string& detail,
                     const oracle::Comparison& c) {
  std::printf(
      "  %-12s %-28s %8llu pixels: %8llu identical, %6llu flagged, %6llu within bound, %6llu "
      "mismatched; colour max %d, mean %.4f\n",
      name.c_str(), detail.c_str(), static_cast<unsigned long long>(c.pixels),
      static_cast<unsigned long long>(c.identical), static_cast<unsigned long long>(c.flagged),
      static_cast<unsigned long long>(c.withinBound), static_cast<unsigned long long>(c.mismatched),
      c.maxColorDifference, c.meanColorDifference);
}

void writeComparisonImages(const std::filesystem::path& folder, const std::string& stem,
                           oracle::Viewport viewport, const oracle::Comparison& c) {
  const auto width = static_cast<uint32_t>(viewport.width),
             height = static_cast<uint32_t>(viewport.height);
  writeImage8(folder / (stem + "-color-difference.png"), width, height, 4,
              std::as_bytes(std::span(c.colorDifferenceImage)));
  writeImage8(folder / (stem + "-classes.png"), width, height, 4,
              std::as_bytes(std::span(c.classificationImage)));
}

}  // namespace vt
