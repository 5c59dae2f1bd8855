#include "scene/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace vt {

Camera flyCamera(const Camera& camera, const FlyInput& input, float seconds, float speed) {
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  glm::vec3 forward = glm::normalize(camera.target - camera.position);
  float yaw = std::atan2(forward.x, -forward.z);
  float pitch = std::asin(std::clamp(forward.y, -1.0f, 1.0f));
  constexpr float kMaxPitch = 1.5533430f;  // 89 degrees
  yaw += input.look.x;
  pitch = std::clamp(pitch + input.look.y, -kMaxPitch, kMaxPitch);
  forward =
      glm::vec3(std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
  const glm::vec3 right = glm::normalize(glm::cross(forward, up));
  Camera moved = camera;
  moved.position +=
      seconds * speed * (input.move.x * right + input.move.y * up + input.move.z * forward);
  moved.target = moved.position + forward;
  moved.up = up;
  return moved;
}

}  // namespace vt
