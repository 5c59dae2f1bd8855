// The viewer's mouse-and-keyboard flight, and its HUD text.

#include "scene/fly_camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gl/hud_text.h"

namespace vt {
namespace {

Camera lookingAlongMinusZ() {
  Camera camera;
  camera.position = {1, 2, 3};
  camera.target = {1, 2, 2};
  return camera;
}

TEST(FlyCamera, MovesAlongTheViewItsRightAndUp) {
  const Camera moved = flyCamera(lookingAlongMinusZ(), {{1, 1, 1}, {0, 0}}, 0.5f, 4.0f);
  // Two units each way: right is +x, forward -z, up +y.
  EXPECT_NEAR(moved.position.x, 3.0f, 1e-5f);
  EXPECT_NEAR(moved.position.y, 4.0f, 1e-5f);
  EXPECT_NEAR(moved.position.z, 1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(moved.target - moved.position), 1.0f, 1e-5f);
}

TEST(FlyCamera, TurnsRightAndKeepsThePitchOffThePoles) {
  const Camera turned = flyCamera(lookingAlongMinusZ(), {{0, 0, 0}, {1.5707963f, 0}}, 1.0f, 1.0f);
  const glm::vec3 forward = turned.target - turned.position;
  EXPECT_NEAR(forward.x, 1.0f, 1e-5f);  // a quarter turn right: from -z to +x
  EXPECT_NEAR(forward.z, 0.0f, 1e-5f);
  const Camera up = flyCamera(lookingAlongMinusZ(), {{0, 0, 0}, {0, 10.0f}}, 1.0f, 1.0f);
  EXPECT_NEAR(glm::degrees(std::asin((up.target - up.position).y)), 89.0f, 1e-3f);
}

TEST(HudText, DrawsTheFontsPixelsWhiteOnBlackRowsFromTheBottom) {
  const HudImage image = renderHudText({"T1", "%"}, 1);
  EXPECT_EQ(image.width, 2u * 6 + 4);
  EXPECT_EQ(image.height, 2u * 9 + 4);
  const auto white = [&](uint32_t x, uint32_t yFromTop) {
    return image.rgba[(size_t(image.height - 1 - yFromTop) * image.width + x) * 4] == 255;
  };
  // 'T': its top row is five pixels wide, its stem one pixel in the middle.
  for (uint32_t x = 2; x < 7; ++x) EXPECT_TRUE(white(x, 2));
  EXPECT_TRUE(white(4, 8));
  EXPECT_FALSE(white(2, 8));
  EXPECT_FALSE(white(0, 0));  // the panel's margin
  EXPECT_EQ(image.rgba[3], 255);
}

}  // namespace
}  // namespace vt
