#pragma once
// One configuration flying a camera path (thesis figure 3.5, chapter 4's setup), frame by frame,
// after the frame is drawn: the analysis of its needbuffer (with the configuration's prediction:
// hot spot, LookAhead camera), its quality against the reference image when one is given, the
// streaming for the next frame and the management step that applies it. Whoever draws the frames
// drives it: a flight drawing each frame itself (eval/flight.h: vt fly, vt golden, vt inspect),
// an evaluation drawing each view once for every configuration (eval/evaluation.h), or the
// interactive viewer drawing into a window (vt view).

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "eval/flight.h"
#include "eval/image_metrics.h"

namespace vt {

// What the drawing step produced for one frame of one configuration.
struct DrawnFrame {
  std::span<const uint8_t> color{};      // RGBA8 at the screen's size; empty when not drawn
  std::span<const glm::uvec4> need{};    // empty: no needbuffer yet (asynchronous readback)
  std::span<const float> depth{};        // with `need`, when the heuristic reads depth
  std::span<const glm::uvec4> lookAheadNeed{};  // the LookAhead camera's, when configured
  std::span<const uint8_t> reference{};  // the reference image, when quality is measured
  // The reference prepared for SSIM once for every run that compares with it; null: prepared here.
  const PreparedReference* preparedReference = nullptr;
  // The needbuffer's size when it is not the run's (an interactive window was resized); 0 x 0: the
  // run's.
  Viewport needViewport{};
  // Replaces the analysis's requests (most important first) before they are streamed: the
  // ceiling of selection (eval/selection_ceiling.h), which the evaluation drives; empty: kept.
  std::function<std::vector<StreamRequest>(std::span<const StreamRequest>,
                                           const VirtualTextureRuntime&)>
      select{};
};

class FlightRun {
 public:
  // The runtime starts with `initialPages` resident (initialPages() below).
  FlightRun(const VirtualTextureReader& reader, const FlightConfiguration& configuration,
            const FlightOptions& options, Viewport needViewport,
            std::span<const uint64_t> initialPages);
  ~FlightRun();

  const VirtualTextureRuntime& runtime() const { return *runtime_; }
  // The frames so far (vt view shows the last one's statistics).
  const std::vector<FlightFrame>& frames() const { return result_.frames; }
  const FlightConfiguration& configuration() const { return configuration_; }

  // Analysis, quality, streaming and management of frame `frameNumber`, drawn from the current
  // cache state; `drawSeconds` is what drawing it cost.
  void frame(int frameNumber, const Camera& previous, const Camera& current,
             const DrawnFrame& drawn, double drawSeconds);

  // The driver adds what it measured outside frame(): reference images, captures.
  FlightTimes& times() { return result_.times; }

  // The result so far; finish() sums the run times.
  FlightResult finish();

 private:
  const FlightConfiguration configuration_;
  const FlightOptions& options_;
  const Viewport needViewport_;
  std::unique_ptr<VirtualTextureRuntime> runtime_;
  std::unique_ptr<PageStreamer> streamer_;
  FlightResult result_;
  uint64_t streamedBefore_ = 0, evictedBefore_ = 0;
};

// The initial cache state of `c` (thesis 4.2.1): levels 0..K-1 and, when asked, every page the
// first frame needs (`firstNeed`: its needbuffer drawn with every page resident at the screen's
// resolution), with trilinear parents first when the configuration counts them.
std::vector<uint64_t> initialPages(const VirtualTextureReader& reader,
                                   const FlightConfiguration& c,
                                   std::span<const glm::uvec4> firstNeed, bool need8);

}  // namespace vt
