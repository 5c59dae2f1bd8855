// `vt fly` over the real map q3dm6ish (thesis chapter 4 on a Quake 3 map): retextured, built and
// flown along the first turns of its viewpoint tour with the thesis's heuristics by name. Needs
// OpenArena (scripts/fetch-openarena.sh, VT_OPENARENA_DIR); skipped without it, except in CI.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/run_command.h"
#include "openarena_data.h"
#include "test_support.h"

namespace vt {
namespace {

struct CsvTotals {
  int rows = 0;
  uint64_t streamedMax = 0;
  bool hitsPlusMissesAreNeeded = true;
};

CsvTotals readFrames(const std::filesystem::path& file) {
  const test::CsvTable table = test::readCsv(file);
  CsvTotals totals;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const auto value = [&](const char* column) -> uint64_t {
      return std::stoull(table.at(r, column));
    };
    ++totals.rows;
    totals.streamedMax = std::max(totals.streamedMax, value("streamed"));
    totals.hitsPlusMissesAreNeeded &= value("hits") + value("misses") == value("needed_pages");
  }
  return totals;
}

TEST(Q3dm6ishFly, StreamsTheTourWithEveryStrategyByNameWithinItsBudget) {
  VT_REQUIRE_OPENARENA(packages);
  test::ScratchDirectory dir;
  ASSERT_NO_FATAL_FAILURE(test::retextureAndBuildQ3dm6ish(*packages, dir.path()));
  const auto run = [&](const std::vector<std::string>& args) {
    const auto result = test::runCommand(VT_EXECUTABLE, args, dir.path());
    EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
    return result;
  };
  const std::string out = (dir / "q3").string();
  // The first five keyframes of the tour: a turn at the first spawn point, 97 frames.
  std::ifstream tour(out + "/q3dm6ish.path.json");
  nlohmann::json path = nlohmann::json::parse(tour);
  path["keyframes"].erase(path["keyframes"].begin() + 5, path["keyframes"].end());
  std::ofstream(dir / "turn.json") << path.dump();

  const std::vector<std::string> common = {"fly",      (dir / "q3.vt").string(),
                                           "--mesh",   out + "/q3dm6ish.obj",
                                           "--path",   (dir / "turn.json").string(),
                                           "--size",   "160x100",
                                           "--budget", "5"};
  const std::vector<std::vector<std::string>> strategies = {
      {"--heuristic", "pixelsum"},
      {"--heuristic", "hotspot*noisevalue", "--lookahead", "stopfix", "--ancestors", "extern",
       "--noise-skipping"},
      {"--heuristic", "weightedpixel*mipgap", "--ancestors", "intern", "--locked-levels", "4"},
      {"--heuristic", "distance", "--hotspot", "sliding", "--preload-visible"},
      {"--heuristic", "pixelsum*mipgap", "--need-scale", "4", "--lookahead", "plain"}};
  for (size_t s = 0; s < strategies.size(); ++s) {
    SCOPED_TRACE(strategies[s][1]);
    std::vector<std::string> args = common;
    args.insert(args.end(), strategies[s].begin(), strategies[s].end());
    const std::string folder = (dir / ("fly" + std::to_string(s))).string();
    args.insert(args.end(), {"-o", folder});
    run(args);
    const CsvTotals frames = readFrames(folder + "/frames.csv");
    EXPECT_EQ(frames.rows, 97);
    EXPECT_LE(frames.streamedMax, 5u);  // the budget of 4.1.1
    EXPECT_GT(frames.streamedMax, 0u);
    EXPECT_TRUE(frames.hitsPlusMissesAreNeeded);
    std::ifstream summaryFile(folder + "/summary.json");
    const auto summary = nlohmann::json::parse(summaryFile);
    EXPECT_GT(summary["hits"].get<uint64_t>(), 0u);
  }

  // The streaming thread over a slow link in real time also flies the path.
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--streaming", "thread", "--link-latency", "0.01", "--link-bandwidth",
                           "20", "-o", (dir / "thread").string()});
  run(args);
  EXPECT_EQ(readFrames(dir / "thread" / "frames.csv").rows, 97);
}

}  // namespace
}  // namespace vt
