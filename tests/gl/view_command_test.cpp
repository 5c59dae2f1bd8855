// `vt view` under a virtual X server (xvfb-run): a few frames of a played path, a screenshot that
// shows the scene and the HUD, and the recorded camera path readable by `vt fly`.

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "scene/camera_path.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TEST(ViewCommand, FliesUnderXvfbWithAHudAndRecordsItsPath) {
  const std::filesystem::path xvfbRun = "/usr/bin/xvfb-run";
  if (!std::filesystem::exists(xvfbRun)) {
    const char* ci = std::getenv("CI");
    if (ci && std::string(ci) == "true") FAIL() << "xvfb-run is missing in CI";
    GTEST_SKIP() << "xvfb-run not installed (scripts/install-deps.sh installs xvfb)";
  }
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  const auto result = test::runCommand(
      xvfbRun.string(),
      {"-a", "-s", "-screen 0 640x480x24", VT_EXECUTABLE, "view", (dir / "t.vt").string(), "--size",
       "320x200", "--frames", "12", "--recording", "--record", (dir / "recorded.json").string(),
       "--screenshot", (dir / "shot.png").string()},
      dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr("pages streamed"));
  EXPECT_THAT(result.out, HasSubstr("recorded 12 keyframes"));

  auto input = OIIO::ImageInput::open((dir / "shot.png").string());
  ASSERT_TRUE(input);
  const OIIO::ImageSpec spec = input->spec();
  ASSERT_EQ(spec.width, 320);
  ASSERT_EQ(spec.height, 200);
  std::vector<uint8_t> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()));
  // The box room fills the lower half with texture colours; the HUD's panel (black) carries
  // white letters in the top-left corner.
  size_t coloured = 0, hudWhite = 0;
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) {
      const uint8_t* p = &pixels[(size_t(y) * spec.width + x) * spec.nchannels];
      const bool white = p[0] == 255 && p[1] == 255 && p[2] == 255;
      if (y >= 100 && (p[0] | p[1] | p[2]) != 0) ++coloured;
      if (y < 40 && x < 160 && white) ++hudWhite;
    }
  EXPECT_GT(coloured, 320u * 100u / 2);
  EXPECT_GT(hudWhite, 100u);

  const CameraPath recorded = CameraPath::load(dir / "recorded.json");
  EXPECT_EQ(recorded.frameCount(), 12);
}

}  // namespace
}  // namespace vt

namespace vt {
namespace {

// The window executes the same frame plan as vt fly (eval/frame_plan.h): a reduced jittered
// needbuffer, the LookAhead pass and delayed readback, and still shows the view (the last pass).
TEST(ViewCommand, ExecutesTheFramePlanOfItsConfiguration) {
  const std::filesystem::path xvfbRun = "/usr/bin/xvfb-run";
  if (!std::filesystem::exists(xvfbRun)) {
    const char* ci = std::getenv("CI");
    if (ci && std::string(ci) == "true") FAIL() << "xvfb-run is missing in CI";
    GTEST_SKIP() << "xvfb-run not installed (scripts/install-deps.sh installs xvfb)";
  }
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  const auto result = test::runCommand(
      xvfbRun.string(),
      {"-a", "-s", "-screen 0 640x480x24", VT_EXECUTABLE, "view", (dir / "t.vt").string(), "--size",
       "320x200", "--frames", "12", "--need-scale", "2", "--lookahead", "stopfix", "--readback",
       "async", "--screenshot", (dir / "shot.png").string()},
      dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr("pages streamed"));
  auto input = OIIO::ImageInput::open((dir / "shot.png").string());
  ASSERT_TRUE(input);
  const OIIO::ImageSpec spec = input->spec();
  ASSERT_EQ(spec.width, 320);
  std::vector<uint8_t> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()));
  // The lower half shows the room at the screen's resolution, not a reduced needbuffer pass.
  size_t coloured = 0;
  for (int y = 100; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) {
      const uint8_t* p = &pixels[(size_t(y) * spec.width + x) * spec.nchannels];
      coloured += (p[0] | p[1] | p[2]) != 0;
    }
  EXPECT_GT(coloured, 320u * 100u * 9 / 10);
}

}  // namespace
}  // namespace vt
