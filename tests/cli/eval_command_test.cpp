// `vt eval`: configurations from comma lists or a JSON file with figures, the files it writes,
// and the errors for configuration files that cannot be run, before anything is flown.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

struct EvalCommandFixture {
  test::ScratchDirectory dir;
  EvalCommandFixture() {
    writeSyntheticTexture(
        dir / "t.vt",
        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  }
  test::CommandResult eval(std::vector<std::string> args) {
    args.insert(args.begin(), {"eval", (dir / "t.vt").string(), "--size", "64x40"});
    return test::runCommand(VT_EXECUTABLE, args, dir.path());
  }
};

TEST(EvalCommand, FliesTheProductOfTheListsAndWritesTablesAndPlots) {
  EvalCommandFixture f;
  const auto result = f.eval({"--heuristic", "pixelsum,random", "--budget", "2,4", "--jobs", "2",
                              "-o", (f.dir / "out").string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("evaluated 4 configurations over 51 frames"));
  std::ifstream csv(f.dir / "out" / "frames.csv");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 1 + 4 * 51);
  std::ifstream md(f.dir / "out" / "summary.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  for (const char* label :
       {"| pixelsum 2/frame |", "| pixelsum 4/frame |", "| random 2/frame |", "| random 4/frame |"})
    EXPECT_THAT(text, HasSubstr(label));
  for (const char* plot :
       {"ssim.svg", "ssim.png", "wssim.svg", "wssim.png", "rmse.svg", "rmse.png"})
    EXPECT_TRUE(std::filesystem::is_regular_file(f.dir / "out" / plot)) << plot;
}

TEST(EvalCommand, DrawsTheFiguresOfAConfigurationsFile) {
  EvalCommandFixture f;
  std::ofstream(f.dir / "c.json") << R"({"defaults": {"budget": 2},
    "configurations": [{"name": "A", "heuristic": "pixelsum"}, {"name": "B", "heuristic": "hotspot",
                        "lookahead": "stopfix"}],
    "figures": [{"file": "ab.png", "title": "A and B", "measure": "wssim", "runs": ["B", "A"]}]})";
  const auto result =
      f.eval({"--configs", (f.dir / "c.json").string(), "-o", (f.dir / "out").string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  // The file name's stem names both drawings.
  EXPECT_TRUE(std::filesystem::is_regular_file(f.dir / "out" / "ab.png"));
  EXPECT_TRUE(std::filesystem::is_regular_file(f.dir / "out" / "ab.svg"));
  const nlohmann::json summary =
      nlohmann::json::parse(std::ifstream(f.dir / "out" / "summary.json"));
  EXPECT_EQ(summary["runs"][1]["configuration"]["lookahead"], "stopfix");
  EXPECT_EQ(summary["runs"][1]["configuration"]["budget"], 2);
}

// The plots need python3 with matplotlib ($VT_PYTHON names a missing interpreter here): the
// evaluation then fails with one line naming the problem and the folder asked for, exit 1, and
// leaves no output folder.
TEST(EvalCommand, FailsWithOneLineAndNoFolderWhenThePlotsCannotBeDrawn) {
  EvalCommandFixture f;
  ::setenv("VT_PYTHON", (f.dir / "no-python").c_str(), 1);
  const auto result = f.eval({"--budget", "2", "-o", (f.dir / "out").string()});
  ::unsetenv("VT_PYTHON");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.err, HasSubstr("vt: error: plots of " + (f.dir / "out").string() +
                                    ": cannot run " + (f.dir / "no-python").string()));
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_FALSE(std::filesystem::exists(f.dir / "out"));
}

TEST(EvalCommand, RefusesBadConfigurationFilesBeforeFlying) {
  EvalCommandFixture f;
  const auto refuse = [&](const std::string& text, const std::string& message) {
    std::ofstream(f.dir / "bad.json") << text;
    const auto result =
        f.eval({"--configs", (f.dir / "bad.json").string(), "-o", (f.dir / "out").string()});
    EXPECT_EQ(result.exitCode, 1) << text;
    EXPECT_THAT(result.err, HasSubstr("bad.json: " + message));
    EXPECT_FALSE(std::filesystem::exists(f.dir / "out")) << text;
  };
  refuse(R"({"configurations": [{"budgt": 3}]})", "configuration 1: unknown configuration key");
  refuse(R"({"configurations": [{"name": "A"}, {"name": "A", "budget": 3}]})",
         "configuration 2: the name 'A' is taken");
  refuse(R"({"configurations": [{"name": "A"}], "figures": [{"file": "x.png", "runs": ["B"]}]})",
         "figure 'x.png': no configuration named 'B'");
  refuse(R"({"configurations": []})", "expected a non-empty list of configurations");
  refuse(R"({"configurations": [{"budget": 3}])", "not a configurations file");
  for (const std::vector<std::string>& option :
       {std::vector<std::string>{"--budget", "3"}, {"--hotspot", "fixed"}, {"--preload-visible"},
        {"--initial-levels", "2"}, {"--noise-skipping"}}) {
    std::vector<std::string> args = {"--configs", (f.dir / "bad.json").string()};
    args.insert(args.end(), option.begin(), option.end());
    const auto both = f.eval(args);
    EXPECT_EQ(both.exitCode, 1) << option[0];
    EXPECT_THAT(both.err, HasSubstr("give either --configs or " + option[0]));
  }
}

// --cache-frames with a configurations file sets every configuration's cache, the ones that name
// their own included; without it the file's sizes stand.
TEST(EvalCommand, CacheFramesSetsTheCacheOfEveryConfigurationOfAFile) {
  EvalCommandFixture f;
  std::ofstream(f.dir / "c.json") << R"({"defaults": {"budget": 2, "cache_frames": 5},
    "configurations": [{"name": "A"}, {"name": "B", "cache_frames": 7}]})";
  const auto cacheSides = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"--configs", (f.dir / "c.json").string(), "-o",
                                     (f.dir / "out").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = f.eval(args);
    EXPECT_EQ(result.exitCode, 0) << result.err;
    const nlohmann::json summary =
        nlohmann::json::parse(std::ifstream(f.dir / "out" / "summary.json"));
    return std::vector<int>{summary["runs"][0]["configuration"]["cache_frames"].get<int>(),
                            summary["runs"][1]["configuration"]["cache_frames"].get<int>()};
  };
  EXPECT_EQ(cacheSides({}), (std::vector<int>{5, 7}));
  EXPECT_EQ(cacheSides({"--cache-frames", "3"}), (std::vector<int>{3, 3}));
}

}  // namespace
}  // namespace vt
