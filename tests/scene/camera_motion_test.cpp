#include "scene/camera_motion.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

Camera at(glm::vec3 position, glm::vec3 target) {
  Camera camera;
  camera.position = position;
  camera.target = target;
  return camera;
}

TEST(CameraMotion, LookAheadRepeatsTheLastMotion) {
  const Camera a = at({0, 0, 0}, {0, 0, -1}), b = at({1, 0, 0}, {1, 0, -1}),
               c = at({2, 0, 0}, {2.5f, 0, -1});
  const Camera plain = lookAheadCamera(a, b, c, LookAhead::kPlain);
  EXPECT_EQ(plain.position, glm::vec3(3, 0, 0));
  EXPECT_EQ(plain.target, glm::vec3(4, 0, -1));
  EXPECT_EQ(lookAheadCamera(a, b, c, LookAhead::kNone).position, c.position);
}

TEST(CameraMotion, StopFixPredictsSteadyMotionAndNotASuddenOne) {
  const Camera a = at({0, 0, 0}, {0, 0, -1}), b = at({1, 0, 0}, {1, 0, -1}),
               c = at({2, 0, 0}, {2, 0, -1});
  // Steady: the change of motion is zero, the step is predicted in full.
  EXPECT_EQ(lookAheadCamera(a, b, c, LookAhead::kStopFix).position, glm::vec3(3, 0, 0));
  // A fast turn that starts from rest: the second derivative equals the motion, no prediction.
  const Camera rest = at({0, 0, 0}, {0, 0, -1}), turned = at({0, 0, 0}, {-1, 0, 0});
  const Camera fixedUp = lookAheadCamera(rest, rest, turned, LookAhead::kStopFix);
  EXPECT_EQ(fixedUp.target, turned.target);
  // Without the fix the same turn is predicted twice over (the thesis's 45 -> 90 degrees).
  EXPECT_EQ(lookAheadCamera(rest, rest, turned, LookAhead::kPlain).target, glm::vec3(-2, 0, 1));
}

TEST(CameraMotion, HotSpotMovesTowardsTheTurn) {
  const Viewport viewport{200, 100};
  const Camera ahead = at({0, 0, 0}, {0, 0, -1});
  const Camera leftABit = at({0, 0, 0}, {-0.1f, 0, -1});  // a small turn to the left
  EXPECT_EQ(hotSpot(ahead, ahead, viewport, HotSpotMode::kShifted), glm::vec2(100, 50));
  EXPECT_EQ(hotSpot(ahead, leftABit, viewport, HotSpotMode::kFixed), glm::vec2(100, 50));
  EXPECT_EQ(hotSpot(ahead, leftABit, viewport, HotSpotMode::kShifted), glm::vec2(0, 50));
  const glm::vec2 sliding = hotSpot(ahead, leftABit, viewport, HotSpotMode::kSliding);
  EXPECT_GT(sliding.x, 0.0f);  // part of the way, in proportion to the turn
  EXPECT_LT(sliding.x, 100.0f);
  EXPECT_EQ(sliding.y, 50.0f);
  // Each refusal names the value of --lookahead or --hot-spot it could not read.
  EXPECT_THAT([] { parseLookAhead("far"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("lookahead 'far' is not one of ")));
  EXPECT_THAT([] { parseHotSpotMode("wobbly"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("hot spot 'wobbly' is not one of ")));
}

}  // namespace
}  // namespace vt
