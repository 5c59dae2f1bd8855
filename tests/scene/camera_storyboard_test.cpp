// Camera paths with named motions (thesis 4.2.1's storyboard): expansion into keyframes, the
// documented interpolation, and the errors a user sees for paths that cannot be flown.

#include "scene/camera_storyboard.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "test_support.h"

namespace vt {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

json storyboard(json motions) {
  return {{"start", {{"position", {1.0, 1.5, 2.0}}, {"yaw", 0}, {"pitch", 0}, {"fov", 70}}},
          {"storyboard", std::move(motions)}};
}

std::string storyboardError(const json& document) {
  try {
    expandStoryboard(document);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(CameraStoryboard, ExpandsMotionsIntoKeyframesAndFrameRanges) {
  const CameraPath path = expandStoryboard(storyboard(json::array({
      {{"name", "1"}, {"kind", "fast rotation that stops"}, {"yaw", 45}, {"frames", 1}},
      {{"kind", "hold"}, {"frames", 10}},
      {{"name", "2"}, {"kind", "translation"}, {"move", {0, 0, 3}}, {"frames", 30}},
      {{"name", "3"}, {"kind", "slow rotation"}, {"yaw", -60}, {"pitch", 10}, {"frames", 40}},
      {{"name", "4"}, {"kind", "corridor walk"}, {"distance", 4}, {"frames", 20}},
  })));
  EXPECT_EQ(path.frameCount(), 102);
  ASSERT_EQ(path.motions().size(), 4u);  // the unnamed hold is no motion of its own
  EXPECT_EQ(path.motions()[0].first, 0);
  EXPECT_EQ(path.motions()[0].last, 1);
  EXPECT_EQ(path.motions()[1].first, 11);
  EXPECT_EQ(path.motions()[1].last, 41);
  EXPECT_EQ(path.motions()[3].kind, "corridor walk");
  EXPECT_EQ(path.motions()[3].last, 101);

  // Motion 1 turns 45 degrees left in one frame, then the camera stands still.
  EXPECT_NEAR(yawPitchOf(path.at(1)).x, 45.0f, 1e-4f);
  EXPECT_EQ(path.at(5).target, path.at(11).target);
  // Motion 2 moves 3 units forward, along the view direction after the turn: (-sin 45, 0, -cos 45).
  const glm::vec3 moved = path.at(41).position - path.at(11).position;
  EXPECT_NEAR(moved.x, -3.0f * std::sqrt(0.5f), 1e-5f);
  EXPECT_NEAR(moved.z, -3.0f * std::sqrt(0.5f), 1e-5f);
  // Motion 3 turns at constant angular speed: half way, half the turn.
  EXPECT_NEAR(yawPitchOf(path.at(61)).x, 15.0f, 1e-3f);
  EXPECT_NEAR(yawPitchOf(path.at(61)).y, 5.0f, 1e-3f);
  // The corridor walk keeps the height although the camera looks 10 degrees up.
  EXPECT_NEAR(path.at(101).position.y, path.at(81).position.y, 1e-6f);
  EXPECT_NEAR(glm::length(path.at(101).position - path.at(81).position), 4.0f, 1e-5f);
}

TEST(CameraStoryboard, AngleKeyframesTurnAtConstantSpeedTargetKeyframesInterpolateTheTarget) {
  Keyframe a, b;
  a.camera.position = b.camera.position = glm::vec3(0.0f);
  a.yawPitch = glm::vec2(0.0f, 0.0f);
  b.yawPitch = glm::vec2(270.0f, 0.0f);  // three quarters to the left, not a quarter right
  a.camera.target = a.camera.position + viewDirection(*a.yawPitch);
  b.camera.target = b.camera.position + viewDirection(*b.yawPitch);
  b.frame = 30;
  const CameraPath turn({a, b});
  EXPECT_NEAR(yawPitchOf(turn.at(10)).x, 90.0f, 1e-3f);
  EXPECT_NEAR(std::abs(yawPitchOf(turn.at(20)).x), 180.0f, 1e-3f);

  a.yawPitch.reset();
  b.yawPitch.reset();
  a.camera.target = {0.0f, 0.0f, -1.0f};
  b.camera.target = {-1.0f, 0.0f, 0.0f};
  const CameraPath targets({a, b});
  EXPECT_NEAR(targets.at(15).target.x, -0.5f, 1e-6f);
  EXPECT_NEAR(targets.at(15).target.z, -0.5f, 1e-6f);
}

TEST(CameraStoryboard, RejectsMotionsThatDoNotMatchTheirNames) {
  EXPECT_THAT(
      storyboardError(storyboard(
          json::array({{{"name", "9"}, {"kind", "slow rotation"}, {"yaw", 90}, {"frames", 10}}}))),
      HasSubstr("motion 1 ('9'): turns 9.000000 degrees per frame, a slow rotation at most"));
  EXPECT_THAT(storyboardError(storyboard(
                  json::array({{{"kind", "fast rotation"}, {"yaw", 10}, {"frames", 10}}}))),
              HasSubstr("a fast rotation more than"));
  EXPECT_THAT(storyboardError(storyboard(
                  json::array({{{"kind", "fast rotation that stops"}, {"yaw", 45}, {"frames", 1}},
                               {{"kind", "slow rotation"}, {"yaw", 10}, {"frames", 10}}}))),
              HasSubstr("must be followed by a hold"));
  EXPECT_THAT(storyboardError(storyboard(json::array({{{"kind", "spin"}, {"frames", 3}}}))),
              HasSubstr("unknown kind 'spin'"));
  EXPECT_THAT(storyboardError(storyboard(json::array({{{"kind", "hold"}, {"frames", 0}}}))),
              HasSubstr("'frames' must be a whole number"));
  EXPECT_THAT(storyboardError(storyboard(json::array({{{"kind", "hold"}, {"frames", 2.5}}}))),
              HasSubstr("'frames' must be a whole number"));
  EXPECT_THAT(storyboardError(storyboard(json::array(
                  {{{"kind", "translation"}, {"move", {0, 0, 1}}, {"speed", 2}, {"frames", 2}}}))),
              HasSubstr("unknown key 'speed'"));
  EXPECT_THAT(storyboardError(storyboard(
                  json::array({{{"kind", "slow rotation"}, {"pitch", 95}, {"frames", 60}}}))),
              HasSubstr("the pitch leaves (-90, 90) degrees"));
  EXPECT_THAT(storyboardError(storyboard(json::array())), HasSubstr("has no motions"));
  EXPECT_THAT(storyboardError(storyboard(
                  json::array({{{"kind", "translation"}, {"move", {0, 0, 1e39}}, {"frames", 2}}}))),
              HasSubstr("not finite"));
}

std::string loadError(const std::string& text) {
  test::ScratchDirectory dir;
  std::ofstream(dir / "path.json") << text;
  try {
    CameraPath::load(dir / "path.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(CameraStoryboard, PathFilesWithNanEmptyOrFallingFramesAreRejectedNamingTheFile) {
  EXPECT_THAT(loadError(R"({"keyframes": []})"), HasSubstr("path.json: the path has no keyframes"));
  EXPECT_THAT(loadError(R"({"keyframes": [{"frame": 0, "position": [0, 0, NaN], "yaw": 0,
                           "pitch": 0}]})"),
              HasSubstr("path.json: not a camera path"));
  EXPECT_THAT(loadError(R"({"keyframes": [
                {"frame": 5, "position": [0, 0, 0], "yaw": 0, "pitch": 0},
                {"frame": 5, "position": [1, 0, 0], "yaw": 0, "pitch": 0}]})"),
              HasSubstr("keyframe 1: frame 5 does not rise above 5"));
  EXPECT_THAT(loadError(R"({"keyframes": [
                {"frame": 0, "position": [0, 0, 0], "target": [1, 0, 0], "yaw": 3}]})"),
              HasSubstr("give either a target or yaw and pitch"));
  EXPECT_THAT(loadError(R"({"keyframes": [
                {"frame": 0, "position": [0, 0, 0], "yaw": 0, "pitch": 0},
                {"frame": 9, "position": [1, 0, 0], "yaw": 0, "pitch": 0}],
              "motions": [{"name": "7", "kind": "translation", "first": 3, "last": 12}]})"),
              HasSubstr("motion '7': frames 3 to 12 do not lie in the path's 0 to 9"));
  EXPECT_THAT(loadError(R"({"start": {"position": [0, 0, 0]}, "storyboard": [
                {"kind": "hold", "frames": 3}, {"kind": "jump", "frames": 3}]})"),
              HasSubstr("path.json: motion 2: unknown kind 'jump'"));
}

TEST(CameraStoryboard, SavedPathsLoadBackWithAnglesAndMotions) {
  const CameraPath path = expandStoryboard(storyboard(json::array(
      {{{"name", "turn"}, {"kind", "slow rotation"}, {"yaw", 30}, {"frames", 20}},
       {{"name", "walk"}, {"kind", "corridor walk"}, {"distance", 2}, {"frames", 20}}})));
  test::ScratchDirectory dir;
  saveCameraPath(dir / "saved.json", path.keyframes(), path.motions());
  const CameraPath loaded = CameraPath::load(dir / "saved.json");
  ASSERT_EQ(loaded.frameCount(), path.frameCount());
  ASSERT_EQ(loaded.motions().size(), 2u);
  EXPECT_EQ(loaded.motions()[1].name, "walk");
  for (int f = 0; f < path.frameCount(); ++f) {
    EXPECT_EQ(loaded.at(f).position, path.at(f).position) << f;
    EXPECT_EQ(loaded.at(f).target, path.at(f).target) << f;
  }
}

}  // namespace
}  // namespace vt
