// `vt golden check --backend gl`: the GL path against the golden images the oracle recorded. On
// llvmpipe (with FMA, which the oracle's llvmpipe profile relies on) every frame must match bit
// for bit, over the real map q3dm6ish's goldens and over a small generated set; elsewhere the
// check runs within the profile's colour bound.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "openarena_data.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kData = std::filesystem::path(VT_TEST_SOURCE_DIR) / ".." / "data";

bool exactOnThisMachine(const std::string& checkOutput) {
  return checkOutput.find("profile llvmpipe") != std::string::npos &&
         __builtin_cpu_supports("fma");
}

TEST(GoldenBackend, TheGlPathPassesTheOracleGoldensOfASmallFlight) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  std::ofstream(dir / "quad.obj") << "v -2 -1 -3\nv 2 -1 -3\nv 2 1.5 -6\nv -2 1.5 -6\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  std::ofstream(dir / "path.json") << R"({"start": {"position": [0, 0, 0], "yaw": 0, "pitch": -5},
    "storyboard": [{"name": "turn", "kind": "fast rotation", "yaw": 30, "frames": 6},
                   {"name": "walk", "kind": "corridor walk", "distance": 1.5, "frames": 20}]})";
  const auto run = [&](const std::vector<std::string>& args) {
    return test::runCommand(VT_EXECUTABLE, args, dir.path());
  };
  const auto generated =
      run({"golden", "generate", (dir / "t.vt").string(), "--mesh", (dir / "quad.obj").string(),
           "--path", (dir / "path.json").string(), "--size", "96x64", "--budget", "3",
           "--profile", "llvmpipe", "--every", "5", "-o", (dir / "golden").string()});
  ASSERT_EQ(generated.exitCode, 0) << generated.err;
  const auto checked =
      run({"golden", "check", (dir / "golden").string(), "--texture", (dir / "t.vt").string(),
           "--mesh", (dir / "quad.obj").string(), "--path", (dir / "path.json").string(),
           "--backend", "gl", "-o", (dir / "check").string()});
  if (exactOnThisMachine(checked.out)) {
    EXPECT_EQ(checked.exitCode, 0) << checked.out << checked.err;
    EXPECT_THAT(checked.out, HasSubstr("6 of 6 frames pass"));
  }
}

TEST(GoldenBackend, TheGlPathPassesQ3dm6ishsGoldens) {
  VT_REQUIRE_OPENARENA(packages);
  test::ScratchDirectory dir;
  ASSERT_NO_FATAL_FAILURE(test::retextureAndBuildQ3dm6ish(*packages, dir.path()));
  const auto checked = test::runCommand(
      VT_EXECUTABLE,
      {"golden", "check", (kData / "golden" / "q3dm6ish").string(), "--texture",
       (dir / "q3.vt").string(), "--mesh", (dir / "q3" / "q3dm6ish.obj").string(), "--path",
       (kData / "paths" / "q3dm6ish.storyboard.json").string(), "--backend", "gl", "-o",
       (dir / "check").string()},
      dir.path());
  if (exactOnThisMachine(checked.out)) {
    EXPECT_EQ(checked.exitCode, 0) << checked.out << checked.err;
    EXPECT_THAT(checked.out, HasSubstr("10 of 10 frames pass"));
  }
}

}  // namespace
}  // namespace vt
