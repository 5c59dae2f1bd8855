#pragma once
// Camera paths for flythroughs (thesis 4.1.2, docs/design.md section 5): keyframes (frame number,
// position, orientation, optional field of view) and named motions over frame ranges.
//
// The JSON form:
//   { "keyframes": [ { "frame": 0, "position": [x, y, z], "target": [x, y, z], "fov": 60 },
//                    { "frame": 40, "position": [x, y, z], "yaw": 90, "pitch": -5 }, ... ],
//     "motions": [ { "name": "9: fast turn", "kind": "fast rotation", "first": 0, "last": 40 } ] }
// or a storyboard of motions from a start pose (scene/camera_storyboard.h), which expands to this.
//
// Orientation: a target point, or yaw and pitch in degrees (yaw about +y, 0 looking down -z,
// positive turning left seen from above; pitch positive looking up, within (-90, 90)).
// Interpolation per frame between neighbouring keyframes: the position linearly; where both
// keyframes give yaw and pitch, the angles linearly (a turn at constant angular speed, the way
// motions are specified; a yaw of 0 to 270 turns three quarters left, not one right); otherwise
// the target point linearly. The field of view linearly. Before the first and after the last
// keyframe the camera holds still.
// Checks, with errors naming the file and the keyframe: at least one keyframe, frames rising
// strictly from 0 or more and below kMaxCameraPathFrames (common/resource_limits.h), every number
// finite, a camera that does not look at its own position,
// a field of view in (0, 180), motions inside the path with first <= last and a known kind.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/camera.h"

namespace vt {

struct Keyframe {
  int frame = 0;
  Camera camera;
  std::optional<glm::vec2> yawPitch;  // degrees, when the orientation was given as angles
};

// The kinds of named motion (thesis 4.2.1's storyboard): hold, translation, slow rotation, fast
// rotation, fast rotation that stops (at once, after the turn), corridor walk.
bool isMotionKind(const std::string& kind);

struct NamedMotion {
  std::string name;         // e.g. "9: fast turn towards the corridor"
  std::string kind;         // isMotionKind
  int first = 0, last = 0;  // frames, inclusive
};

class CameraPath {
 public:
  // Both throw std::invalid_argument.
  explicit CameraPath(std::vector<Keyframe> keyframes, std::vector<NamedMotion> motions = {});
  static CameraPath load(const std::filesystem::path& file);  // throws InputError
  // The JSON text of a path held in memory, `file` naming it in errors; throws InputError.
  static CameraPath parse(std::string_view text, const std::filesystem::path& file);

  int frameCount() const { return keyframes_.back().frame + 1; }
  Camera at(int frame) const;
  const std::vector<Keyframe>& keyframes() const { return keyframes_; }
  const std::vector<NamedMotion>& motions() const { return motions_; }

 private:
  std::vector<Keyframe> keyframes_;
  std::vector<NamedMotion> motions_;
};

// The unit view direction of yaw and pitch in degrees (convention above).
glm::vec3 viewDirection(glm::vec2 yawPitchDegrees);
// Yaw and pitch of a camera's view direction, in degrees.
glm::vec2 yawPitchOf(const Camera& camera);

// Writes the keyframes and motions in the JSON form above (through a temporary file renamed at
// the end).
void saveCameraPath(const std::filesystem::path& file, const std::vector<Keyframe>& keyframes,
                    const std::vector<NamedMotion>& motions = {});

// A slow turn around the box room with a stop and a fast turn (the default path of `vt fly`).
CameraPath boxRoomPath();

}  // namespace vt
