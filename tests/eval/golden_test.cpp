// Golden images (eval/golden.h): a set generated from a flight checks against the same flight,
// and fails, naming the frame, when a frame's colour changes or the inputs are not the golden's.

#include "eval/golden.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "common/error.h"
#include "eval/box_room_scene.h"
#include "test_support.h"
#include "render/arithmetic_points.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

struct GoldenFixture {
  test::ScratchDirectory dir;
  GoldenRequest request;
  GoldenFixture() {
    writeSyntheticTexture(
        dir / "t.vt",
        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
    test::writeBoxRoomScene(dir.path());
    request.texture = dir / "t.vt";
    request.mesh = dir / "room.obj";
    request.path = dir / "path.json";
    request.configuration.budget = 3;
    request.viewport = {64, 40};
    request.every = 7;
  }
  GoldenCheck check(const std::filesystem::path& texture) {
    return checkGolden(dir / "golden", texture, request.mesh, request.path, Backend::kOracle,
                       std::nullopt, dir / "report");
  }
};

TEST(Golden, ASetChecksAgainstTheFlightItCameFrom) {
  GoldenFixture f;
  generateGolden(f.request, f.dir / "golden");
  const nlohmann::json golden =
      nlohmann::json::parse(std::ifstream(f.dir / "golden" / "golden.json"));
  ASSERT_EQ(golden["frames"].size(), 5u);  // frames 0, 7, 14, 21, 28 of 29
  EXPECT_EQ(golden["frames"][4]["frame"], 28);
  EXPECT_TRUE(std::filesystem::is_regular_file(f.dir / "golden" / "frame0028.png"));
  const GoldenCheck result = f.check(f.request.texture);
  EXPECT_TRUE(result.passed());
  for (const GoldenFrameCheck& frame : result.frames) {
    EXPECT_TRUE(frame.colorMatches && frame.needMatches && frame.qualityMatches) << frame.frame;
    EXPECT_EQ(frame.pixelsDiffering, 0u) << frame.frame;
  }
}

TEST(Golden, AChangedFrameFailsAndGetsADifferenceImage) {
  GoldenFixture f;
  generateGolden(f.request, f.dir / "golden");
  nlohmann::json golden = nlohmann::json::parse(std::ifstream(f.dir / "golden" / "golden.json"));
  golden["frames"][2]["color"] = "0123456789abcdef";
  std::ofstream(f.dir / "golden" / "golden.json") << golden.dump();
  const GoldenCheck result = f.check(f.request.texture);
  EXPECT_FALSE(result.passed());
  for (const GoldenFrameCheck& frame : result.frames) EXPECT_EQ(frame.passed, frame.frame != 14);
  EXPECT_TRUE(std::filesystem::is_regular_file(f.dir / "report" / "frame0014.difference.png"));
  const nlohmann::json report =
      nlohmann::json::parse(std::ifstream(f.dir / "report" / "check.json"));
  EXPECT_FALSE(report["passed"].get<bool>());
}

TEST(Golden, AnotherTextureOrPathIsRefusedWithTheReason) {
  GoldenFixture f;
  generateGolden(f.request, f.dir / "golden");
  writeSyntheticTexture(
      f.dir / "other.vt",
      {{.pageSize = 32, .border = 2, .levelCount = 5, .channels = 4}, std::nullopt});
  try {
    f.check(f.dir / "other.vt");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("the goldens were made from another texture"));
  }
  std::ofstream(f.request.path, std::ios::app) << "\n";
  try {
    f.check(f.request.texture);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("path.json: its checksum"));
  }
}

}  // namespace
}  // namespace vt
