// `vt demo`, the main job: it draws with OpenGL, so it lives with the GL tests (under the
// sanitizers they run without leak checking: tests/CMakeLists.txt says why).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/run_command.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TEST(DemoCommand, BuildsRendersWithBothRenderersAndComparesThem) {
  test::ScratchDirectory dir_;
  const auto vt = [&](const std::vector<std::string>& args) {
    return test::runCommand(VT_EXECUTABLE, args, dir_.path());
  };
  const auto result = vt({"demo", "--output", (dir_ / "demo").string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("4096 x 4096 texels, levels 0..5"));
  EXPECT_THAT(result.out, HasSubstr("every checksum matches"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "demo" / "scene" / "layout.json"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "demo" / "level4.png"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "demo" / "frame.png"));
  // Both renderers draw the box room; on llvmpipe they agree on every pixel.
  if (result.out.find("llvmpipe") != std::string::npos) {
    EXPECT_THAT(result.out, HasSubstr("cross-check: colour identical in 230400 of 230400 pixels, "
                                      "needbuffer identical in 230400"));
  }
  // The default scene is generated the same way every time.
  const auto first = test::readBytes(dir_ / "demo" / "scene.vt");
  ASSERT_EQ(vt({"demo", "--output", (dir_ / "again").string()}).exitCode, 0);
  EXPECT_EQ(test::readBytes(dir_ / "again" / "scene.vt"), first);
}

}  // namespace
}  // namespace vt
