#pragma once
// An evaluation (thesis 4.1): several configurations flown over the same camera path, each frame
// measured against its reference image (every needed page resident, docs/design.md section 5). The
// runs fly in lockstep: each view is drawn once for all of them (its reference image, needbuffer
// and depth; reference/recolor.h shades it under each run's cache state), then every run analyses,
// streams and measures its frame, in parallel. The per-frame results are the bytes of flights of
// their own (eval/flight.h), for any number of jobs.

#include <functional>
#include <vector>

#include "eval/flight.h"
#include "eval/image_metrics.h"

namespace vt {

struct EvaluationRun {
  FlightConfiguration configuration;
  FlightResult result;
  uint32_t cacheSide = 0;  // the cache's N x N frames (cacheFramesFor)
};

// Called from the calling thread with the frames done so far (references and flights together)
// out of `total`.
using EvaluationProgress = std::function<void(uint64_t done, uint64_t total)>;

struct EvaluationOptions {
  RenderSettings settings;  // the screen, profile, need8; threads are set per stage
  unsigned jobs = 0;        // runs at once; 0: every core
  EvaluationProgress progress;
  // The texture whose frames with every page resident are the references, when not the flown
  // one: the same pages in another format (a compressed texture judged against the uncompressed
  // one, so that the encoding's error counts); requireSamePages says which may be.
  const VirtualTextureReader* reference = nullptr;
};

struct Evaluation {
  std::vector<EvaluationRun> runs;  // in the order of the configurations
  double viewSeconds = 0.0;     // drawing each view once (the reference images and needbuffers)
  double recolorSeconds = 0.0;  // shading the views under every run's cache state
  double wallSeconds = 0.0;     // the whole evaluation
  // With a reference texture: each frame of the flown texture with every page resident against
  // the reference, the encoding's own error apart from the streaming's; and the time its
  // reference frames took to draw.
  std::vector<SsimAndWssim> encoding;
  double referenceSeconds = 0.0;
};

// Throws InputError naming `reference` unless its pages are the flown texture's: the same page
// size, border and levels (the pixel format may differ).
void requireSamePages(const VirtualTextureReader& flown, const VirtualTextureReader& reference);

// An evaluation flies its runs in lockstep, each run's cache texture and colour buffer held at
// once: throws limitError (common/resource_limits.h) naming `origin` (the configurations' file)
// when they exceed kMaxEvaluationStateBytes, before anything is drawn.
void requireEvaluationFits(const std::filesystem::path& origin, const TextureDescription& texture,
                           Viewport screen, const std::vector<FlightConfiguration>& configurations);

// Throws what a flight throws (the first error of any run).
Evaluation evaluate(const VirtualTextureReader& reader, const Mesh& mesh, const CameraPath& path,
                    const std::vector<FlightConfiguration>& configurations,
                    const EvaluationOptions& options);

// Quality of frames [first, last] of a run: mean and minimum SSIM, mean WSSIM and RMSE.
struct RangeQuality {
  double meanSsim = 0.0, minSsim = 1.0, meanWssim = 0.0, meanRmse = 0.0;
};
RangeQuality rangeQuality(const FlightResult& result, int first, int last);

}  // namespace vt
