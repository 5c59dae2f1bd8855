// A heuristic is parsed once: its factors in the order written, its text written back the same,
// and a bad factor refused with the message the command line and configuration files show.

#include "runtime/heuristic.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

namespace vt {
namespace {

std::string heuristicError(const std::string& text) {
  try {
    Heuristic::parse(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Heuristic, KeepsTheFactorsInTheOrderWritten) {
  const Heuristic h = Heuristic::parse("hotspot*noisevalue*distance");
  EXPECT_EQ(h.factors(),
            (std::vector<PriorityFactor>{PriorityFactor::kHotSpot, PriorityFactor::kNoiseValue,
                                         PriorityFactor::kDistance}));
  EXPECT_TRUE(h.uses(PriorityFactor::kDistance));
  EXPECT_FALSE(h.uses(PriorityFactor::kPixelSum));
  EXPECT_EQ(Heuristic(), Heuristic::parse("pixelsum"));
}

TEST(Heuristic, WritesEveryFactorBackAsRead) {
  for (const auto& [factor, name] : kPriorityFactorNames) {
    EXPECT_EQ(Heuristic::parse(name).text(), name);
    EXPECT_EQ(Heuristic::parse(name).factors(), std::vector{factor});
  }
  EXPECT_EQ(Heuristic::parse("weightedpixel*mipgap").text(), "weightedpixel*mipgap");
}

TEST(Heuristic, RefusesUnknownAndEmptyFactorsWithTheirMessage) {
  EXPECT_EQ(heuristicError(""), "heuristic: empty");
  EXPECT_EQ(heuristicError("pixelsum*speed"),
            "heuristic: 'speed' is not one of random, pixelsum, distance, weightedpixel, hotspot, "
            "noisevalue, mipgap");
  EXPECT_THAT(heuristicError("pixelsum**distance"),
              testing::HasSubstr("heuristic: '' is not one of"));
  EXPECT_THAT(heuristicError("Pixelsum"), testing::HasSubstr("'Pixelsum' is not one of"));
}

}  // namespace
}  // namespace vt
