#pragma once
// What one frame of a flight draws, decided in one place for every driver: fly() (vt fly, vt
// golden, vt inspect), evaluate() (vt eval, which draws each distinct pass once for all its runs)
// and vt view (whose camera comes from the window instead of a path). The configuration decides
// it, never the backend or the command:
//   the view        the frame's camera at the screen's resolution (its colour)
//   the needbuffer  the analysis's input: the view itself, or at 1/2^k of the screen per axis with
//                   this frame's jitter (runtime/needbuffer_scale.h) in a pass of its own
//   the LookAhead   with a LookAhead mode, the predicted camera's needbuffer at the same scale
//                   and jitter (scene/camera_motion.h)
//   the readback    synchronous, or delayed by a frame (the analysis reads the previous frame's
//                   needbuffer and depth)
// The reference image a frame's quality is measured against is the view drawn by the oracle with
// every page resident in the flight's own arithmetic (flight.h, referenceImage), in every driver.

#include <cstdint>
#include <optional>
#include <utility>

#include "eval/flight_configuration.h"
#include "scene/camera.h"
#include "scene/camera_path.h"
#include "scene/clip_space_mesh.h"

namespace vt {

struct NeedPass {
  LookAhead camera = LookAhead::kNone;  // kNone: the frame's own camera
  int scaleLog2 = 0;
  Camera view;        // the camera drawn
  Viewport viewport;  // the screen reduced by 2^scaleLog2 per axis
  glm::vec2 jitter{0.0f};
  // Passes with the same key draw the same image in one frame (an evaluation draws each once).
  std::pair<LookAhead, int> key() const { return {camera, scaleLog2}; }
};

struct FramePlan {
  uint64_t frame = 0;
  Viewport screen;
  Camera camera, previous;  // the view; the camera of the frame before (the analysis's motion)
  NeedPass need;
  std::optional<NeedPass> lookAhead;
  bool delayedReadback = false;
  // The needbuffer is the view's own (full scale): the pass that draws it draws the view's colour.
  bool needPassIsTheView() const { return need.scaleLog2 == 0; }
};

// Frame `frame` with the cameras of this frame, the one before and the one before that.
FramePlan planFrame(const FlightConfiguration& configuration, Viewport screen, uint64_t frame,
                    const Camera& beforePrevious, const Camera& previous, const Camera& current);
// Frame `frame` of `path` (its first camera stands for the frames before it).
FramePlan planFrame(const FlightConfiguration& configuration, Viewport screen,
                    const CameraPath& path, int frame);

}  // namespace vt
