#pragma once
// vt view's interactive flight (thesis 4.2.1's setup): a window flies through a scene, by hand
// (W A S D, Q E, the left mouse button to look, Shift for speed) or along a path, and streams its
// pages live with the streaming thread over a link model. Each frame draws what its plan says
// (eval/frame_plan.h) on the window's GL renderer, as vt fly would for the same configuration,
// hands the frame to FlightRun and shows the view with a HUD (frame time, pages needed and
// missing, requested and streamed, cache occupancy). R starts and stops recording the camera path.

#include <filesystem>
#include <optional>
#include <ostream>

#include "eval/flight_configuration.h"
#include "format/virtual_texture_reader.h"
#include "gl/window_context.h"
#include "runtime/page_streamer.h"
#include "scene/camera.h"
#include "scene/camera_path.h"
#include "scene/mesh.h"

namespace vt {

struct InteractiveFlight {
  Mesh mesh;
  Camera start;                    // where a flight by hand begins
  std::optional<CameraPath> path;  // played instead of flying by hand
  FlightConfiguration configuration;
  LinkModel link;
  double speed = 3.0;                // world units per second (Shift: 4x)
  int maxFrames = 0;                 // quit after this many frames; 0: when the window closes
  bool recordFromStart = false;      // record from the first frame (R stops)
  std::filesystem::path record;      // where recording writes the camera path (.json), if anywhere
  std::filesystem::path screenshot;  // the last frame with the HUD (with maxFrames)
};

// Flies in `window` (its GL context current) until it closes or maxFrames; writes what the flight
// recorded and one line per result to `out`.
void flyInteractively(WindowContext& window, const VirtualTextureReader& reader,
                      const InteractiveFlight& request, std::ostream& out);

}  // namespace vt
