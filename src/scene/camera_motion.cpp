#include "scene/camera_motion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vt {
namespace {

constexpr float kPi = 3.14159265358979f;

// Yaw (around +y, positive to the left) and pitch (positive up) of the viewing direction.
glm::vec2 yawPitch(const Camera& camera) {
  const glm::vec3 d = glm::normalize(camera.target - camera.position);
  return {std::atan2(-d.x, -d.z), std::asin(std::clamp(d.y, -1.0f, 1.0f))};
}

float wrapAngle(float a) {
  while (a > kPi) a -= 2 * kPi;
  while (a < -kPi) a += 2 * kPi;
  return a;
}

}  // namespace

LookAhead parseLookAhead(const std::string& name) {
  if (const auto mode = findByName(kLookAheadNames, name)) return *mode;
  throw std::invalid_argument("lookahead '" + name + "' is not one of " +
                              joinedNames(kLookAheadNames));
}

HotSpotMode parseHotSpotMode(const std::string& name) {
  if (const auto mode = findByName(kHotSpotModeNames, name)) return *mode;
  throw std::invalid_argument("hot spot '" + name + "' is not one of " +
                              joinedNames(kHotSpotModeNames));
}

std::string toString(LookAhead mode) { return std::string(nameOf(kLookAheadNames, mode)); }

std::string toString(HotSpotMode mode) { return std::string(nameOf(kHotSpotModeNames, mode)); }

Camera lookAheadCamera(const Camera& beforePrevious, const Camera& previous, const Camera& current,
                       LookAhead mode) {
  if (mode == LookAhead::kNone) return current;
  const glm::vec3 dp = current.position - previous.position, dt = current.target - previous.target;
  float scale = 1.0f;
  if (mode == LookAhead::kStopFix) {
    const glm::vec3 ap = dp - (previous.position - beforePrevious.position);
    const glm::vec3 at = dt - (previous.target - beforePrevious.target);
    const float speed = std::sqrt(glm::dot(dp, dp) + glm::dot(dt, dt));
    const float change = std::sqrt(glm::dot(ap, ap) + glm::dot(at, at));
    scale = speed > 0.0f ? std::max(0.0f, 1.0f - change / speed) : 0.0f;
  }
  Camera predicted = current;
  predicted.position += scale * dp;
  predicted.target += scale * dt;
  if (predicted.position == predicted.target) return current;
  return predicted;
}

glm::vec2 hotSpot(const Camera& previous, const Camera& current, Viewport viewport,
                  HotSpotMode mode) {
  const glm::vec2 centre(static_cast<float>(viewport.width) * 0.5f,
                         static_cast<float>(viewport.height) * 0.5f);
  if (mode == HotSpotMode::kFixed) return centre;
  const glm::vec2 a = yawPitch(previous), b = yawPitch(current);
  const float yaw = wrapAngle(b.x - a.x), pitch = b.y - a.y;  // turned left (+yaw), up (+pitch)
  const float halfFovY = current.fovYDegrees * kPi / 360.0f;
  const float halfFovX = std::atan(std::tan(halfFovY) * static_cast<float>(viewport.width) /
                                   static_cast<float>(viewport.height));
  glm::vec2 shift;  // in units of half the screen, +x right, +y up
  if (mode == HotSpotMode::kShifted) {
    shift = {yaw > 0 ? -1.0f : (yaw < 0 ? 1.0f : 0.0f),
             pitch > 0 ? 1.0f : (pitch < 0 ? -1.0f : 0.0f)};
  } else {
    shift = {std::clamp(-yaw / halfFovX, -1.0f, 1.0f), std::clamp(pitch / halfFovY, -1.0f, 1.0f)};
  }
  return centre + shift * centre;
}

}  // namespace vt
