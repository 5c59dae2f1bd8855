// Our SSIM against scikit-image's structural_similarity (Debian's python3-skimage, run with
// /usr/bin/python3) on rendered frames: the box room drawn by the oracle with every page resident
// and with only the coarsest levels, the Gaussian 11 x 11 window and a uniform 7 x 7 one
// (scikit-image has no even windows). Agreement within 1e-4 (the bound); the difference
// is in fact rounding.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "eval/image_metrics.h"
#include "openarena_data.h"
#include "reference/renderer.h"
#include "scene/box_room.h"
#include "test_support.h"

namespace vt {
namespace {

void writeDoubles(const std::filesystem::path& file, const std::vector<double>& values) {
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(values.data()),
             static_cast<std::streamsize>(values.size() * sizeof(double)));
}

TEST(SsimReference, AgreesWithScikitImageOnRenderedFrames) {
  const std::filesystem::path python = "/usr/bin/python3";
  test::ScratchDirectory dir;
  const auto probe =
      test::runCommand(python.string(), {"-c", "import skimage.metrics, numpy"}, dir.path());
  if (probe.exitCode != 0) {
    if (test::runningInCi()) FAIL() << "python3-skimage is missing in CI: " << probe.err;
    GTEST_SKIP() << "python3-skimage not installed (scripts/install-deps.sh installs it)";
  }
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  const VirtualTextureReader reader(dir / "t.vt");
  RenderSettings settings;
  settings.viewport = {160, 96};
  const ClipSpaceMesh mesh = toClipSpace(boxRoom(), boxRoomCamera(), settings.viewport);
  const Frame all = reference::renderFrame(mesh, reference::ResidentTexture(reader), settings);
  const Frame coarse = reference::renderFrame(mesh, cacheOfLevels(reader, 2, 4096), settings);
  const ImageView a{settings.viewport.width, settings.viewport.height, all.color};
  const ImageView b{settings.viewport.width, settings.viewport.height, coarse.color};
  writeDoubles(dir / "a.f64", luminance(a));
  writeDoubles(dir / "b.f64", luminance(b));
  const auto result = test::runCommand(
      python.string(),
      {std::string(VT_TEST_SOURCE_DIR) + "/eval/skimage_ssim.py", (dir / "a.f64").string(),
       (dir / "b.f64").string(), std::to_string(a.width), std::to_string(a.height)},
      dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  double gaussian = 0.0, uniform7 = 0.0;
  std::istringstream(result.out) >> gaussian >> uniform7;
  const double ours = ssim(a, b, {.window = SsimWindow::kGaussian});
  EXPECT_LT(ours, 0.99);  // the frames differ: a meaningful comparison
  EXPECT_NEAR(ours, gaussian, 1e-4);
  EXPECT_NEAR(ssim(a, b, {.window = SsimWindow::kUniform, .uniformSize = 7}), uniform7, 1e-4);
}

TEST(SsimReference, WssimWeighsTheScreenCentre) {
  // A difference only near the corners lowers SSIM but hardly WSSIM; identical images give 1.
  std::vector<uint8_t> a(64 * 48 * 4, 0), b;
  for (size_t i = 0; i < a.size(); ++i) a[i] = static_cast<uint8_t>((i * 37) % 251);
  b = a;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) b[(static_cast<size_t>(y) * 64 + x) * 4 + c] ^= 0x55;
  const ImageView va{64, 48, a}, vb{64, 48, b};
  EXPECT_DOUBLE_EQ(wssim(va, va), 1.0);
  EXPECT_LT(ssim(va, vb), 1.0);
  EXPECT_GT(wssim(va, vb), ssim(va, vb));
}

}  // namespace
}  // namespace vt
