// `vt render --backend gl` against `--backend oracle`: the same scene from the same cache state;
// on llvmpipe (with the llvmpipe profile on an FMA CPU) the images are identical byte for byte.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TEST(RenderBackend, GlAndOracleImagesAgree) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 5, .channels = 4}, std::nullopt});
  const auto render = [&](const std::string& backend) {
    return test::runCommand(
        VT_EXECUTABLE,
        {"render", (dir / "t.vt").string(), "--backend", backend, "--profile", "llvmpipe", "--size",
         "200x120", "-o", (dir / (backend + ".png")).string()},
        dir.path());
  };
  const auto gl = render("gl");
  ASSERT_EQ(gl.exitCode, 0) << gl.err;
  EXPECT_THAT(gl.out, HasSubstr("(gl: "));
  const auto oracle = render("oracle");
  ASSERT_EQ(oracle.exitCode, 0) << oracle.err;
  if (gl.out.find("llvmpipe") != std::string::npos && __builtin_cpu_supports("fma")) {
    EXPECT_EQ(test::readBytes(dir / "gl.png"), test::readBytes(dir / "oracle.png"));
  }
}

}  // namespace
}  // namespace vt
