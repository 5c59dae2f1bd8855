#pragma once
// A flight (thesis chapter 4's setup): a camera path frame by frame with streaming. Each frame is
// drawn from the current cache state, its needbuffer analysed and prioritised, and pages streamed
// for the next frame, under one FlightConfiguration. Optionally each frame's quality against its
// reference image (every needed page resident, docs/design.md section 5), measured apart from the
// flight's run time.
//
// Per-frame results are the same for any thread count and for either backend under the
// llvmpipe profile on llvmpipe (tests/gl/fly_backend_test.cpp); in the streaming thread's real-time
// mode they depend on timing.

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "eval/flight_configuration.h"
#include "format/virtual_texture_reader.h"
#include "backends/backend.h"
#include "runtime/page_streamer.h"
#include "runtime/virtual_texture_runtime.h"
#include "scene/camera_path.h"
#include "scene/mesh.h"

namespace vt {

struct FrameQuality {
  double rmse = 0.0, ssim = 0.0, wssim = 0.0;  // eval/image_metrics.h; SSIM 8 x 8 uniform
};

struct FlightFrame {
  FrameStatistics statistics;
  std::optional<FrameQuality> quality;
};

// Where a flight's time went, in seconds summed over its frames. The flight: drawing the frame
// (colour and needbuffer, and the LookAhead camera's needbuffer), analysing its needbuffer and
// choosing pages, streaming and applying them. Measuring its quality: the reference image, RMSE
// and SSIM/WSSIM, and the rest (captures, observers). In an evaluation the views are drawn once
// for every configuration (eval/evaluation.h); each run's drawing time counts that shared pass
// whole, as a flight of its own would pay it, and its reference time is zero (the evaluation
// reports the shared pass).
struct FlightTimes {
  double draw = 0.0, analysis = 0.0, streaming = 0.0;
  double reference = 0.0, metrics = 0.0, other = 0.0;
};

struct FlightResult {
  std::vector<FlightFrame> frames;
  FrameStatistics totals;  // hits, misses, streamed and evicted summed over the frames
  FlightTimes times;
  double seconds = 0.0;         // the flight: draw + analysis + streaming
  double qualitySeconds = 0.0;  // reference + metrics + other
};

// What the flight saw in one frame, for observers (frame images, the inspector). Valid during the
// call; the runtime is in the state the frame was drawn and analysed with, before the pages
// streamed for the next frame are applied.
struct FlightFrameView {
  int frame = 0;
  std::span<const uint8_t> color;  // RGBA8 rows bottom to top, when asked (wantsColor)
  std::span<const glm::uvec4> need;
  Viewport needViewport;
  std::span<const uint8_t> reference;  // the reference image, when this frame's quality is measured
  const std::vector<StreamRequest>& requests;
  std::span<const uint64_t> streamed;  // pages that arrive for the next frame
  const VirtualTextureRuntime& runtime;
  const FlightFrame& result;
};

// A frame drawn again for a capture (vt fly --capture): the current camera at the screen's full
// resolution, from the cache state the flight drew the frame with, by the flight's backend.
struct FlightCaptureView {
  int frame = 0;
  const ClipSpaceMesh& mesh;
  std::span<const uint8_t> color;  // RGBA8 rows bottom to top
  std::span<const glm::uvec4> need;
  const VirtualTextureRuntime& runtime;
};

struct FlightOptions {
  RenderSettings settings;             // viewport (the screen), profile, threads, need8
  Backend backend = Backend::kOracle;  // GL: a current context is the caller's
  bool threadedStreaming = false;  // a streaming thread in real time over `link`, not the budget
  LinkModel link;
  // The reference image of a frame (RGBA8, rows bottom to top, the screen's size); when set,
  // each frame's quality is measured against it, except where it returns no image (callers that
  // look at a few frames only draw no reference for the others).
  std::function<std::vector<uint8_t>(int frame)> reference;
  std::function<bool(int frame)> wantsColor;  // also keep the colour when no reference asks it
  std::function<void(const FlightFrameView&)> observe;
  bool keepAnalysis = false;  // let observers ask the runtime for priority terms
  // Frames to capture and what to do with each; their time counts as quality time, not flight.
  std::function<bool(int frame)> wantsCapture;
  std::function<void(const FlightCaptureView&)> capture;
  // Flies frames 0 to lastFrame only (a shard of a golden check stops at its last frame); -1:
  // every frame of the path. The frames flown are those of the whole flight.
  int lastFrame = -1;
  // The driver draws each frame's next view and picks pages with it (DrawnFrame::select): only
  // then may a configuration's selection be the ceiling (an evaluation; eval/evaluation.h).
  bool drawsNextView = false;
};

FlightResult fly(const VirtualTextureReader& reader, const Mesh& mesh, const CameraPath& path,
                 const FlightConfiguration& configuration, const FlightOptions& options);

// The frame drawn with every page resident, at `settings`' viewport: the reference image.
std::vector<uint8_t> referenceImage(const ResidentRenderer& everything, const Mesh& mesh,
                                    const Camera& camera, const RenderSettings& settings);

}  // namespace vt
