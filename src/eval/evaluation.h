#pragma once
// An evaluation (thesis 4.1): several configurations flown over the same camera path, each frame
// measured against its reference image (every needed page resident, DESIGN section 5). The runs
// fly in lockstep: each view is drawn once for all of them (its reference image, needbuffer and
// depth; reference/recolor.h shades it under each run's cache state), then every run analyses,
// streams and measures its frame, in parallel. The per-frame results are the bytes of flights of
// their own (eval/flight.h), for any number of jobs.

#include <functional>
#include <vector>

#include "eval/flight.h"

namespace vt {

struct EvaluationRun {
  FlightConfiguration configuration;
  FlightResult result;
};

// Called from the calling thread with the frames done so far (references and flights together)
// out of `total`.
using EvaluationProgress = std::function<void(uint64_t done, uint64_t total)>;

struct EvaluationOptions {
  RenderSettings settings;  // the screen, profile, need8; threads are set per stage
  unsigned jobs = 0;        // runs at once; 0: every core
  EvaluationProgress progress;
};

struct Evaluation {
  std::vector<EvaluationRun> runs;  // in the order of the configurations
  double viewSeconds = 0.0;     // drawing each view once (the reference images and needbuffers)
  double recolorSeconds = 0.0;  // shading the views under every run's cache state
  double wallSeconds = 0.0;     // the whole evaluation
};

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
