#pragma once
// `vt fly`'s work as one call: a camera path flown with streaming (eval/flight.h) into an output
// folder (frames.csv, summary.json, timing.json, every n-th frame as an image) and, when asked, a
// capture folder for `vt crosscheck --captures` (verify/flight_capture.h). Both folders are
// written as temporary folders that take their places once the flight is complete: a failure,
// early or late, leaves the previous outputs or none.

#include <filesystem>
#include <ostream>
#include <string>

#include "backends/backend.h"
#include "eval/flight.h"
#include "eval/flight_configuration.h"
#include "scene/camera_path.h"
#include "scene/mesh.h"

namespace vt {

struct FlyRequest {
  std::filesystem::path texture;  // as given, for the summary
  Mesh mesh;
  CameraPath path;
  FlightConfiguration configuration;
  Viewport screen{320, 200};
  unsigned threads = 0;  // the oracle's (0: every core)
  Backend backend = Backend::kOracle;
  std::string profile = "auto";    // a point's name, or auto (workflows/auto_model.h)
  bool threadedStreaming = false;  // a streaming thread in real time over the link
  double linkLatencySeconds = 0, linkMegabytesPerSecond = 0;
  bool quality = false;  // RMSE, SSIM and WSSIM per frame
  int imagesEvery = 0;   // every n-th frame as frameNNNN.png (0: none)
  std::filesystem::path output;
  std::filesystem::path capture;  // empty: no captures
  int captureEvery = 1;
};

// Flies and writes; messages (a model note, the totals) go to `out` and `err`.
FlightResult flyToFolder(const VirtualTextureReader& reader, const FlyRequest& request,
                         std::ostream& out, std::ostream& err);

}  // namespace vt
