// `vt crosscheck` in CI: every named scene with both renderers on the driver at hand; on llvmpipe
// every pixel must be identical, and the summary records the settings results depend on.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TEST(CrosscheckCommand, EveryScenePassesAndTheSummaryRecordsTheSettings) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt",
                        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  const auto result = test::runCommand(
      VT_EXECUTABLE,
      {"crosscheck", (dir / "t.vt").string(), "--size", "160x100", "-o", (dir / "out").string()},
      dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr("0 mismatched: passed"));
  std::ifstream in(dir / "out" / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["passed"], true);
  EXPECT_EQ(summary["frames"].size(), 10u);  // five scenes, two modes
  EXPECT_EQ(summary["settings"]["LP_NUM_THREADS"], "2");
  EXPECT_TRUE(summary["settings"].contains("GALLIVM_PERF"));
  EXPECT_TRUE(summary["settings"].contains("GALLIUM_OVERRIDE_CPU_CAPS"));
  if (summary["gl_renderer"].get<std::string>().find("llvmpipe") != std::string::npos &&
      summary["profile"] == "llvmpipe") {
    EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
  }
  EXPECT_TRUE(
      std::filesystem::exists(dir / "out" / "horizon-texelfetch-trilinear-need32-classes.png"));
}

TEST(CrosscheckCommand, UnknownSceneIsAnError) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 16, .border = 1, .levelCount = 3, .channels = 4}, std::nullopt});
  const auto result = test::runCommand(
      VT_EXECUTABLE, {"crosscheck", (dir / "t.vt").string(), "--scenes", "room,moon"}, dir.path());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.err, HasSubstr("scene 'moon' is not one of"));
}

}  // namespace
}  // namespace vt
