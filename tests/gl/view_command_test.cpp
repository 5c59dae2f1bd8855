// `vt view` under a virtual X server (xvfb-run): a few frames of a played path, a screenshot that
// shows the scene and the HUD, the recorded camera path readable by `vt fly`, and the frame plan
// of its configuration executed as vt fly executes it.

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

struct Screenshot {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;  // rows top to bottom
  const uint8_t* at(int x, int y) const {
    return &pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels)];
  }
  // Pixels of rows [y0, y1) that are not black.
  size_t coloured(int y0, int y1) const {
    size_t count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < width; ++x) count += (at(x, y)[0] | at(x, y)[1] | at(x, y)[2]) != 0;
    return count;
  }
};

class ViewCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kXvfbRun)) {
      const char* ci = std::getenv("CI");
      if (ci && std::string(ci) == "true") FAIL() << "xvfb-run is missing in CI";
      GTEST_SKIP() << "xvfb-run not installed (scripts/install-deps.sh installs xvfb)";
    }
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  }

  // 12 frames of the box room at 320 x 200 with `options`, the last one as a screenshot.
  test::CommandResult view(const std::vector<std::string>& options) {
    std::vector<std::string> args = {"-a",          "-s",           "-screen 0 640x480x24",
                                     VT_EXECUTABLE, "view",         (dir_ / "t.vt").string(),
                                     "--size",      "320x200",      "--frames",
                                     "12",          "--screenshot", (dir_ / "shot.png").string()};
    args.insert(args.end(), options.begin(), options.end());
    return test::runCommand(kXvfbRun.string(), args, dir_.path());
  }

  Screenshot screenshot() const {
    Screenshot shot;
    auto input = OIIO::ImageInput::open((dir_ / "shot.png").string());
    if (!input) return shot;
    const OIIO::ImageSpec spec = input->spec();
    shot.width = spec.width, shot.height = spec.height, shot.channels = spec.nchannels;
    shot.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, shot.pixels.data()))
      shot.pixels.clear();
    return shot;
  }

  inline static const std::filesystem::path kXvfbRun = "/usr/bin/xvfb-run";
  test::ScratchDirectory dir_;
};

TEST_F(ViewCommand, FliesUnderXvfbWithAHudAndRecordsItsPath) {
  const auto result = view({"--recording", "--record", (dir_ / "recorded.json").string()});
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr("pages streamed"));
  EXPECT_THAT(result.out, HasSubstr("recorded 12 keyframes"));

  const Screenshot shot = screenshot();
  ASSERT_EQ(shot.width, 320);
  ASSERT_EQ(shot.height, 200);
  // The box room fills the lower half with texture colours; the HUD's panel (black) carries
  // white letters in the top-left corner.
  size_t hudWhite = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 160; ++x) {
      const uint8_t* p = shot.at(x, y);
      hudWhite += p[0] == 255 && p[1] == 255 && p[2] == 255;
    }
  EXPECT_GT(shot.coloured(100, 200), 320u * 100u / 2);
  EXPECT_GT(hudWhite, 100u);

  const CameraPath recorded = CameraPath::load(dir_ / "recorded.json");
  EXPECT_EQ(recorded.frameCount(), 12);
}

// The window executes the same frame plan as vt fly (eval/frame_plan.h): a reduced jittered
// needbuffer, the LookAhead pass and delayed readback, and still shows the view (the last pass).
TEST_F(ViewCommand, ExecutesTheFramePlanOfItsConfiguration) {
  const auto result = view({"--need-scale", "2", "--lookahead", "stopfix", "--readback", "async"});
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr("pages streamed"));
  const Screenshot shot = screenshot();
  ASSERT_EQ(shot.width, 320);
  // The lower half shows the room at the screen's resolution, not a reduced needbuffer pass.
  EXPECT_GT(shot.coloured(100, 200), 320u * 100u * 9 / 10);
}

}  // namespace
}  // namespace vt
