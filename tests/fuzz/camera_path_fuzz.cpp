// Fuzz target: camera paths (scene/camera_path.h), keyframes or storyboards, and the camera at
// the frames a flythrough renders.

#include <string_view>

#include "fuzz/fuzz_targets.h"
#include "scene/camera_path.h"

namespace vt::fuzz {

void cameraPath(Input input) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  const CameraPath path = CameraPath::parse(text, "/nonexistent/vt-fuzz/path.json");
  // The first and last frames, one past them, and the middle.
  const int last = path.frameCount() - 1;
  for (const int frame : {-1, 0, last / 2, last, last + 1}) path.at(frame);
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::cameraPath)
