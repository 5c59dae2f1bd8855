#pragma once
// Mouse-and-keyboard flight for the interactive viewer: yaw about the world's up axis, pitch about
// the camera's right axis (kept within 89 degrees of the horizon), movement along the view
// direction, its right and the world's up.

#include <glm/glm.hpp>

#include "scene/camera.h"

namespace vt {

struct FlyInput {
  glm::vec3 move{0.0f};  // x right, y up, z forward, each in [-1, 1]
  glm::vec2 look{0.0f};  // radians: x turns right, y looks up
};

// The camera after `seconds` of `input` at `speed` world units per second.
Camera flyCamera(const Camera& camera, const FlyInput& input, float seconds, float speed);

}  // namespace vt
