#include "verify/comparison_report.h"

#include <algorithm>
#include <cstdio>

#include "common/image_file.h"

namespace vt {
namespace {

template <class Count>
nlohmann::json byReason(const std::array<Count, oracle::kReasons>& counts) {
  nlohmann::json result = nlohmann::json::object();
  for (int r = 0; r < oracle::kReasons; ++r)
    result[oracle::reasonName(r)] = counts[static_cast<size_t>(r)];
  return result;
}

// What each parameter would have to widen by, for the parameters any unexplained pixel names.
nlohmann::json widenings(const std::array<uint64_t, oracle::kReasons>& unexplainedBy,
                         const std::array<double, oracle::kReasons>& widenBy) {
  nlohmann::json result = nlohmann::json::object();
  for (int r = 0; r < oracle::kReasons; ++r)
    if (unexplainedBy[static_cast<size_t>(r)] != 0)
      result[oracle::reasonName(r)] = {{"pixels", unexplainedBy[static_cast<size_t>(r)]},
                                       {"widen_by", widenBy[static_cast<size_t>(r)]},
                                       {"unit", oracle::widthUnit(r)}};
  return result;
}

double fraction(uint64_t part, uint64_t whole) {
  return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

// Written next to "ambiguous_fraction" in every record.
void addWidths(nlohmann::json& record, const SetWidths& widths) {
  record["covered"] = widths.covered;
  record["mean_color_width"] = widths.meanColorWidth();
  record["mean_candidate_levels"] = widths.meanLevels();
  record["mean_candidate_pages"] = widths.meanPages();
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", value);
  return text;
}

}  // namespace

uint64_t setPixels(const oracle::Comparison& c) {
  return c.judged ? c.pixels - c.identical : c.pixels;
}

void ComparisonTotals::add(const oracle::Comparison& c, const SetWidths& frameWidths) {
  pixels += c.pixels;
  identical += c.identical;
  explained += c.explained;
  unexplained += c.unexplained;
  ambiguous += c.ambiguous;
  setPixels += vt::setPixels(c);
  judged = judged || c.judged;
  for (size_t r = 0; r < oracle::kReasons; ++r) {
    explainedBy[r] += c.explainedBy[r];
    unexplainedBy[r] += c.unexplainedBy[r];
    widenBy[r] = std::max(widenBy[r], c.widenBy[r]);
  }
  widths.add(frameWidths);
}

void ComparisonTotals::add(const ComparisonTotals& other) {
  pixels += other.pixels;
  identical += other.identical;
  explained += other.explained;
  unexplained += other.unexplained;
  ambiguous += other.ambiguous;
  setPixels += other.setPixels;
  judged = judged || other.judged;
  for (size_t r = 0; r < oracle::kReasons; ++r) {
    explainedBy[r] += other.explainedBy[r];
    unexplainedBy[r] += other.unexplainedBy[r];
    widenBy[r] = std::max(widenBy[r], other.widenBy[r]);
  }
  widths.add(other.widths);
}

nlohmann::json ComparisonTotals::record() const {
  return {{"pixels", pixels},
          {"identical", identical},
          {"explained", explained},
          {"unexplained", unexplained},
          {"ambiguous", ambiguous},
          {"set_pixels", setPixels},
          {"judged", judged},
          {"explained_by", explainedBy},
          {"unexplained_by", unexplainedBy},
          {"widen_by", widenBy},
          {"covered", widths.covered},
          {"color_width_sum", widths.colorWidthSum},
          {"level_sum", widths.levelSum},
          {"page_sum", widths.pageSum}};
}

ComparisonTotals ComparisonTotals::fromRecord(const nlohmann::json& record) {
  ComparisonTotals totals;
  record.at("pixels").get_to(totals.pixels);
  record.at("identical").get_to(totals.identical);
  record.at("explained").get_to(totals.explained);
  record.at("unexplained").get_to(totals.unexplained);
  record.at("ambiguous").get_to(totals.ambiguous);
  record.at("set_pixels").get_to(totals.setPixels);
  record.at("judged").get_to(totals.judged);
  record.at("explained_by").get_to(totals.explainedBy);
  record.at("unexplained_by").get_to(totals.unexplainedBy);
  record.at("widen_by").get_to(totals.widenBy);
  record.at("covered").get_to(totals.widths.covered);
  record.at("color_width_sum").get_to(totals.widths.colorWidthSum);
  record.at("level_sum").get_to(totals.widths.levelSum);
  record.at("page_sum").get_to(totals.widths.pageSum);
  return totals;
}

double ComparisonTotals::ambiguousFraction() const { return fraction(ambiguous, setPixels); }

nlohmann::json ComparisonTotals::json() const {
  nlohmann::json record = {{"pixels", pixels},
                           {"identical", identical},
                           {"explained", explained},
                           {"unexplained", unexplained},
                           {"ambiguous", ambiguous},
                           {"ambiguous_fraction", ambiguousFraction()},
                           {"set_pixels", setPixels},
                           {"sets", judged ? "differing pixels" : "every pixel"},
                           {"explained_by", byReason(explainedBy)},
                           {"unexplained_by", widenings(unexplainedBy, widenBy)}};
  addWidths(record, widths);
  return record;
}

std::string ComparisonTotals::line() const {
  char text[360];
  std::snprintf(text, sizeof text,
                "%llu of %llu pixels identical, %llu explained, %llu unexplained; ambiguous "
                "fraction %.4f, colour width %.4f/255, %.4f levels, %.4f pages%s",
                static_cast<unsigned long long>(identical), static_cast<unsigned long long>(pixels),
                static_cast<unsigned long long>(explained),
                static_cast<unsigned long long>(unexplained), ambiguousFraction(),
                widths.meanColorWidth(), widths.meanLevels(), widths.meanPages(),
                judged ? " (of the differing pixels)" : "");
  return text;
}

nlohmann::json comparisonJson(const oracle::Comparison& c, const SetWidths& widths) {
  nlohmann::json record = {{"model", c.model},
                           {"pixels", c.pixels},
                           {"identical", c.identical},
                           {"explained", c.explained},
                           {"unexplained", c.unexplained},
                           {"ambiguous", c.ambiguous},
                           {"ambiguous_fraction", fraction(c.ambiguous, setPixels(c))},
                           {"set_pixels", setPixels(c)},
                           {"sets", c.judged ? "differing pixels" : "every pixel"},
                           {"explained_by", byReason(c.explainedBy)},
                           {"unexplained_by", widenings(c.unexplainedBy, c.widenBy)},
                           {"needbuffer_mismatched", c.needMismatched},
                           {"max_color_difference", c.maxColorDifference},
                           {"mean_color_difference", c.meanColorDifference}};
  addWidths(record, widths);
  return record;
}

std::vector<std::pair<std::string, std::string>> widthProperties(
    const oracle::Comparison& c, const SetWidths& widths) {
  return {{"ambiguous_fraction", number(fraction(c.ambiguous, setPixels(c)))},
          {"set_pixels", std::to_string(setPixels(c))},
          {"covered", std::to_string(widths.covered)},
          {"mean_color_width", number(widths.meanColorWidth())},
          {"mean_candidate_levels", number(widths.meanLevels())},
          {"mean_candidate_pages", number(widths.meanPages())}};
}

void printComparison(const std::string& name, const std::string& detail,
                     const oracle::Comparison& c, const SetWidths& widths) {
  std::printf(
      "  %-12s %-28s %8llu pixels: %8llu identical, %6llu explained, %6llu unexplained, "
      "ambiguous %.4f (width %.4f/255, %.4f levels, %.4f pages%s); colour max %d, mean %.4f\n",
      name.c_str(), detail.c_str(), static_cast<unsigned long long>(c.pixels),
      static_cast<unsigned long long>(c.identical), static_cast<unsigned long long>(c.explained),
      static_cast<unsigned long long>(c.unexplained), fraction(c.ambiguous, setPixels(c)),
      widths.meanColorWidth(), widths.meanLevels(), widths.meanPages(),
      c.judged ? ", of the differing pixels" : "", c.maxColorDifference, c.meanColorDifference);
  for (int r = 0; r < oracle::kReasons; ++r)
    if (c.unexplainedBy[static_cast<size_t>(r)] != 0)
      std::printf("  %-12s %-28s %8llu unexplained pixels need %s widened by %g %s\n", "", "",
                  static_cast<unsigned long long>(c.unexplainedBy[static_cast<size_t>(r)]),
                  oracle::reasonName(r).c_str(), c.widenBy[static_cast<size_t>(r)],
                  oracle::widthUnit(r).c_str());
}

void writeComparisonImages(const std::filesystem::path& folder, const std::string& stem,
                           oracle::Viewport viewport, const oracle::Comparison& c) {
  const auto width = static_cast<uint32_t>(viewport.width),
             height = static_cast<uint32_t>(viewport.height);
  writeImage8(folder / (stem + "-color-difference.png"), width, height, 4,
              std::as_bytes(std::span(c.colorDifferenceImage)), PngCompression::kFast);
  writeImage8(folder / (stem + "-classes.png"), width, height, 4,
              std::as_bytes(std::span(c.classificationImage)), PngCompression::kFast);
}

}  // namespace vt
