// `vt golden check --backend gl`: the GL path against the golden images the oracle recorded. On
// llvmpipe (with FMA, which the oracle's llvmpipe profile relies on) every frame must match bit
// for bit, over the real map q3dm6ish's goldens and over a small generated set; elsewhere (and on
// softpipe, tested here) each frame is judged by the oracle's result sets under the model.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "openarena_data.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kData = std::filesystem::path(VT_TEST_SOURCE_DIR) / ".." / "data";

bool exactOnThisMachine(const std::string& checkOutput) {
  return checkOutput.find("model llvmpipe") != std::string::npos && __builtin_cpu_supports("fma");
}

TEST(GoldenBackend, TheGlPathPassesTheOracleGoldensOfASmallFlight) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  std::ofstream(dir / "quad.obj")
      << "v -2 -1 -3\nv 2 -1 -3\nv 2 1.5 -6\nv -2 1.5 -6\n"
         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  std::ofstream(dir / "path.json") << R"({"start": {"position": [0, 0, 0], "yaw": 0, "pitch": -5},
    "storyboard": [{"name": "turn", "kind": "fast rotation", "yaw": 30, "frames": 6},
                   {"name": "walk", "kind": "corridor walk", "distance": 1.5, "frames": 20}]})";
  const auto run = [&](const std::vector<std::string>& args) {
    return test::runCommand(VT_EXECUTABLE, args, dir.path());
  };
  const auto generated =
      run({"golden", "generate", (dir / "t.vt").string(), "--mesh", (dir / "quad.obj").string(),
           "--path", (dir / "path.json").string(), "--size", "96x64", "--budget", "3", "--profile",
           "llvmpipe", "--every", "5", "-o", (dir / "golden").string()});
  ASSERT_EQ(generated.exitCode, 0) << generated.err;
  const auto checked =
      run({"golden", "check", (dir / "golden").string(), "--texture", (dir / "t.vt").string(),
           "--mesh", (dir / "quad.obj").string(), "--path", (dir / "path.json").string(),
           "--backend", "gl", "-o", (dir / "check").string()});
  // llvmpipe: bit for bit under its pinned model; any other implementation: judged by result sets.
  EXPECT_EQ(checked.exitCode, 0) << checked.out << checked.err;
  EXPECT_THAT(checked.out, HasSubstr("6 of 6 frames pass"));

  // softpipe differs from llvmpipe (no vertex snapping, float filter weights:
  // docs/precision-models.md), so its
  // frames are not the golden images; under gl45 each recorded frame is judged against the
  // oracle's result sets for the cache state it was drawn from, and nothing is unexplained.
  ::setenv("GALLIUM_DRIVER", "softpipe", 1);
  ::setenv("MESA_GL_VERSION_OVERRIDE", "4.5", 1);
  ::setenv("MESA_GLSL_VERSION_OVERRIDE", "450", 1);
  const auto soft =
      run({"golden", "check", (dir / "golden").string(), "--texture", (dir / "t.vt").string(),
           "--mesh", (dir / "quad.obj").string(), "--path", (dir / "path.json").string(),
           "--backend", "gl", "--model", "gl45", "-o", (dir / "soft").string()});
  ASSERT_EQ(soft.exitCode, 0) << soft.out << soft.err;
  EXPECT_THAT(soft.out, HasSubstr("golden check (gl, model gl45): 6 of 6 frames pass"));
  std::ifstream in(dir / "soft" / "check.json");
  const auto check = nlohmann::json::parse(in);
  EXPECT_EQ(check["model"], "gl45");
  uint64_t differing = 0;
  for (const auto& frame : check["frames"]) {
    EXPECT_EQ(frame["unexplained"], 0u);
    differing += frame["pixels_differing"].get<uint64_t>();
  }
  EXPECT_GT(differing, 0u);  // the frames do differ from the golden images: the sets decided
}

TEST(GoldenBackend, TheGlPathPassesQ3dm6ishsGoldens) {
  VT_REQUIRE_OPENARENA(packages);
  test::ScratchDirectory dir;
  ASSERT_NO_FATAL_FAILURE(test::retextureAndBuildQ3dm6ish(*packages, dir.path()));
  const auto checked =
      test::runCommand(VT_EXECUTABLE,
                       {"golden", "check", (kData / "golden" / "q3dm6ish").string(), "--texture",
                        (dir / "q3.vt").string(), "--mesh", (dir / "q3" / "q3dm6ish.obj").string(),
                        "--path", (kData / "golden" / "q3dm6ish.storyboard.json").string(),
                        "--backend", "gl", "-o", (dir / "check").string()},
                       dir.path());
  if (exactOnThisMachine(checked.out)) {
    EXPECT_EQ(checked.exitCode, 0) << checked.out << checked.err;
    EXPECT_THAT(checked.out, HasSubstr("10 of 10 frames pass"));
  }
}

}  // namespace
}  // namespace vt
