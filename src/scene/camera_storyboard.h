#pragma once
// A storyboard: a camera path written as a sequence of named motions from a start pose, the way
// the thesis describes its flythrough (4.2.1, the figure of motions 1 to 15). It expands to
// keyframes with yaw and pitch (scene/camera_path.h), one at the end of each motion, and the
// motions' frame ranges.
//
//   { "start": { "position": [x, y, z], "yaw": 0, "pitch": 0, "fov": 70 },
//     "storyboard": [
//       { "name": "1", "kind": "fast rotation that stops", "yaw": 45, "frames": 1 },
//       { "kind": "hold", "frames": 10 },
//       { "name": "2", "kind": "translation", "move": [0, 0, 1.5], "yaw": 10, "frames": 40 },
//       { "name": "3", "kind": "slow rotation", "yaw": -60, "pitch": 5, "frames": 60 },
//       { "name": "4", "kind": "corridor walk", "distance": 6, "frames": 120 } ] }
//
// Kinds and their parameters (angles in degrees, lengths in scene units, `frames` >= 1):
//   hold                       frames
//   translation                move [right, up, forward] in the camera's axes at the motion's
//                              start; optional yaw, pitch turned on the way
//   slow rotation              yaw, pitch; at most kSlowDegreesPerFrame per frame
//   fast rotation              yaw, pitch; more than kSlowDegreesPerFrame per frame
//   fast rotation that stops   as fast rotation, and the camera stands still right after it: the
//                              next motion is a hold, or there is none (4.2.4.1's worst case)
//   corridor walk              distance along the horizontal view direction, no turning
// A motion's range runs from the frame it starts at (its camera still the previous pose) to the
// frame it ends on, as the thesis's red frame numbers. Errors name the motion.

#include <filesystem>
#include <nlohmann/json_fwd.hpp>

#include "scene/camera_path.h"

namespace vt {

inline constexpr float kSlowDegreesPerFrame = 2.0f;

// Throws std::invalid_argument naming the motion and what is wrong.
CameraPath expandStoryboard(const nlohmann::json& document);

}  // namespace vt
