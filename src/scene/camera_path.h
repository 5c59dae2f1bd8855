#pragma once
// Camera paths for flythroughs: keyframes (frame number, position, target, optional field of
// view), interpolated linearly per frame between neighbouring keyframes; before the first and
// after the last the camera holds still. The JSON form:
//   { "keyframes": [ { "frame": 0, "position": [x, y, z], "target": [x, y, z], "fov": 60 }, ... ] }
// Frames must rise strictly; every number must be finite; a camera must not look at its own
// position. Errors name the file and the keyframe.

#include <filesystem>
#include <vector>

#include "scene/camera.h"

namespace vt {

struct Keyframe {
  int frame = 0;
  Camera camera;
};

class CameraPath {
 public:
  explicit CameraPath(std::vector<Keyframe> keyframes);       // throws std::invalid_argument
  static CameraPath load(const std::filesystem::path& file);  // throws InputError

  int frameCount() const { return keyframes_.back().frame + 1; }
  Camera at(int frame) const;

 private:
  std::vector<Keyframe> keyframes_;
};

// Writes keyframes in the JSON form above (through a temporary file renamed at the end).
void saveCameraPath(const std::filesystem::path& file, const std::vector<Keyframe>& keyframes);

// A slow turn around the box room with a stop and a fast turn (the default path of `vt fly`).
CameraPath boxRoomPath();

}  // namespace vt
