// `vt eval`'s configurations, checked without flying: a configurations file's defaults, labels and
// figures, each mistake refused with the message the command prints, and the product of lists.

#include "eval/configurations_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

std::string configurationsError(const std::string& text) {
  try {
    parseConfigurationsFile(nlohmann::json::parse(text));
  } catch (const std::invalid_argument& e) {
    return e.what();
  } catch (const nlohmann::json::exception& e) {
    return std::string("json: ") + e.what();
  }
  return "";
}

TEST(ConfigurationsFile, DefaultsFillWhatAConfigurationLeavesOut) {
  const ConfigurationsFile file = parseConfigurationsFile(nlohmann::json::parse(R"({
    "defaults": {"budget": 2, "ancestors": "extern"},
    "configurations": [{"name": "A"}, {"heuristic": "hotspot*noisevalue", "budget": 7}],
    "figures": [{"file": "ab.png", "measure": "wssim", "runs": ["hotspot*noisevalue 7/frame extern", "A"]}]})"));
  ASSERT_EQ(file.configurations.size(), 2u);
  EXPECT_EQ(file.configurations[0].budget, 2u);
  EXPECT_EQ(file.configurations[0].ancestors, AncestorStrategy::kExtern);
  EXPECT_EQ(file.configurations[1].budget, 7u);
  EXPECT_EQ(file.configurations[1].heuristic, Heuristic::parse("hotspot*noisevalue"));
  ASSERT_EQ(file.figures.size(), 1u);
  EXPECT_EQ(file.figures[0].title, "ab.png");  // the file when no title is given
  EXPECT_EQ(file.figures[0].measure, "wssim");
  EXPECT_EQ(file.figures[0].runs,
            (std::vector<std::string>{"hotspot*noisevalue 7/frame extern", "A"}));
}

TEST(ConfigurationsFile, APlainListIsAFileWithoutDefaultsOrFigures) {
  const ConfigurationsFile file =
      parseConfigurationsFile(nlohmann::json::parse(R"([{"budget": 3}, {"budget": 4}])"));
  ASSERT_EQ(file.configurations.size(), 2u);
  EXPECT_EQ(file.configurations[1].label(), "pixelsum 4/frame");
  EXPECT_TRUE(file.figures.empty());
}

TEST(ConfigurationsFile, AByteBudgetIsLabelledAndWrittenOnlyWhereSet) {
  const ConfigurationsFile file = parseConfigurationsFile(
      nlohmann::json::parse(R"([{"budget": 3}, {"budget_bytes": 740000}])"));
  ASSERT_EQ(file.configurations.size(), 2u);
  EXPECT_EQ(file.configurations[1].budgetBytes, 740000u);
  EXPECT_EQ(file.configurations[1].label(), "pixelsum 740000B/frame");
  EXPECT_FALSE(file.configurations[0].toJson().contains("budget_bytes"));
  EXPECT_EQ(file.configurations[1].toJson()["budget_bytes"], 740000u);
  const FlightConfiguration back =
      FlightConfiguration::fromJson(file.configurations[1].toJson(), FlightConfiguration{});
  EXPECT_EQ(back.budgetBytes, 740000u);
  EXPECT_EQ(configurationsError(R"([{"budget_bytes": -1}])"),
            "configuration 1: 'budget_bytes' must be a whole number from 0 to 2^40");
}

// A cache of a number of bytes holds more frames of compressed pages: 136^2 texels are 73,984
// bytes as RGBA8, 9,248 as BC1 (an eighth) and 18,496 as BC3.
TEST(ConfigurationsFile, ACacheInBytesHoldsAsManyFramesAsFitAtTheStoredPageSize) {
  const ConfigurationsFile file = parseConfigurationsFile(
      nlohmann::json::parse(R"([{"cache_frames": 8}, {"cache_bytes": 18939904}])"));
  ASSERT_EQ(file.configurations.size(), 2u);
  const FlightConfiguration& bytes = file.configurations[1];
  EXPECT_EQ(bytes.label(), "pixelsum 10/frame cache=18939904B");
  EXPECT_FALSE(file.configurations[0].toJson().contains("cache_bytes"));
  EXPECT_EQ(FlightConfiguration::fromJson(bytes.toJson(), {}).cacheBytes, 18939904u);
  TextureDescription d{.pageSize = 128, .border = 4, .levelCount = 8, .channels = 4};
  EXPECT_EQ(cacheFramesFor(file.configurations[0], d), 8u);
  EXPECT_EQ(cacheFramesFor(bytes, d), 16u);  // 256 frames of 73,984 bytes exactly
  d.format = PixelFormat::kBc3;
  EXPECT_EQ(cacheFramesFor(bytes, d), 32u);  // 1024 frames of 18,496
  d.format = PixelFormat::kBc1;
  EXPECT_EQ(cacheFramesFor(bytes, d), 45u);  // 2048 frames of 9,248: 45^2 = 2025 fit
  // A cache larger than one texture of 16384^2 texels holds (120 frames of 136 texels a side) is
  // cut to it.
  FlightConfiguration huge;
  huge.cacheBytes = uint64_t{1} << 40;
  EXPECT_EQ(cacheFramesFor(huge, d), 120u);
  FlightConfiguration tiny;
  tiny.cacheBytes = 1;
  EXPECT_EQ(cacheFramesFor(tiny, d), 1u);  // never less than one frame
  EXPECT_EQ(configurationsError(R"([{"cache_bytes": 1.5}])"),
            "configuration 1: 'cache_bytes' must be a whole number from 0 to 2^40");
}

TEST(ConfigurationsFile, RefusesEachMistakeWithItsMessage) {
  EXPECT_EQ(configurationsError(R"({"configurations": [{"budgt": 3}]})"),
            "configuration 1: unknown configuration key 'budgt'");
  EXPECT_EQ(
      configurationsError(R"({"configurations": [{"name": "A"}, {"name": "A", "budget": 3}]})"),
      "configuration 2: the name 'A' is taken");
  EXPECT_EQ(configurationsError(R"([{"budget": 3}, {"budget": 3}])"),
            "configuration 2: the name 'pixelsum 3/frame' is taken");
  EXPECT_EQ(configurationsError(R"({"configurations": [{"heuristic": "pixelsum*luck"}]})"),
            "configuration 1: heuristic: 'luck' is not one of random, pixelsum, distance, "
            "weightedpixel, hotspot, noisevalue, mipgap");
  EXPECT_EQ(configurationsError(R"({"configurations": [{"ancestors": "sideways"}]})"),
            "configuration 1: ancestor strategy 'sideways' is not one of none, intern, extern, "
            "gain, gain_ssim");
  EXPECT_EQ(configurationsError(R"({"configurations": []})"),
            "expected a non-empty list of configurations");
  EXPECT_EQ(configurationsError(R"({"configurations": {}})"),
            "expected a non-empty list of configurations");
  EXPECT_EQ(
      configurationsError(
          R"({"configurations": [{"name": "A"}], "figures": [{"file": "x.png", "runs": ["B"]}]})"),
      "figure 'x.png': no configuration named 'B'");
  EXPECT_EQ(
      configurationsError(
          R"({"configurations": [{"name": "A"}], "figures": [{"file": "a/x.png", "runs": []}]})"),
      "figure 'a/x.png': the file must be a plain name.png");
  EXPECT_EQ(
      configurationsError(
          R"({"configurations": [{"name": "A"}], "figures": [{"file": "x.png", "measure": "psnr", "runs": []}]})"),
      "figure 'x.png': measure 'psnr' is not ssim, wssim or rmse");
  EXPECT_THAT(configurationsError(R"({"defaults": {"budget": -1}, "configurations": [{}]})"),
              HasSubstr("'budget' must be a whole number from 0 to 1048576"));
  // Finite as a double, infinite as the float it is kept in (fuzz_config's round trip).
  EXPECT_EQ(configurationsError(R"({"configurations": [{"noise_threshold": 1e300}]})"),
            "configuration 1: 'noise_threshold' must be a finite number (a float)");
  // No configurations key.
  EXPECT_THAT(configurationsError(R"({"defaults": {}})"), HasSubstr("json: "));
}

TEST(ConfigurationsFile, NamesTheFileInItsErrors) {
  test::ScratchDirectory dir;
  std::ofstream(dir / "bad.json") << R"({"configurations": [{"budget": 3}])";
  try {
    loadConfigurationsFile(dir / "bad.json");
    ADD_FAILURE() << "a truncated file was read";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.json: not a configurations file: "));
  }
  std::ofstream(dir / "taken.json") << R"([{"name": "A"}, {"name": "A"}])";
  try {
    loadConfigurationsFile(dir / "taken.json");
    ADD_FAILURE() << "a taken name was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("taken.json: configuration 2: the name 'A' is taken"));
  }
}

TEST(ConfigurationProduct, VariesTheLastListFastest) {
  ConfigurationLists lists;
  lists.heuristics = "pixelsum,random";
  lists.budgets = "2,4";
  lists.parents = "off,on";
  const auto configurations = configurationProduct(lists, FlightConfiguration{});
  ASSERT_EQ(configurations.size(), 8u);
  EXPECT_EQ(configurations[0].label(), "pixelsum 2/frame");
  EXPECT_EQ(configurations[1].label(), "pixelsum 2/frame parents");
  EXPECT_EQ(configurations[2].label(), "pixelsum 4/frame");
  EXPECT_EQ(configurations[7].label(), "random 4/frame parents");
}

TEST(ConfigurationProduct, RefusesBadItems) {
  const auto refuse = [](ConfigurationLists lists, const std::string& message) {
    try {
      configurationProduct(lists, FlightConfiguration{});
      ADD_FAILURE() << message;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  refuse({.parents = "maybe"}, "--trilinear-parents takes off and on, not 'maybe'");
  refuse({.budgets = "x"}, "not a whole number in 'x', '0' or '1'");
  refuse({.heuristics = ","}, "empty list ','");
  refuse({.lookAheads = "far"}, "lookahead 'far' is not one of none, plain, stopfix");
  refuse({.needScales = "3"}, "needbuffer scale '3' is not 1, 2, 4 or 8");
}

}  // namespace
}  // namespace vt
