#pragma once
// An evaluation (thesis 4.1): several configurations flown over the same camera path, each frame
// measured against one shared set of reference images (every needed page resident, DESIGN
// section 5). Independent runs go in parallel, one per job, each drawing with one thread: the
// per-frame results are the same bytes for any number of jobs.

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
  reference::RenderSettings settings;  // the screen, profile, need8; threads are set per stage
  unsigned jobs = 0;                   // runs at once; 0: every core
  EvaluationProgress progress;
};

struct Evaluation {
  std::vector<EvaluationRun> runs;  // in the order of the configurations
  double referenceSeconds = 0.0;    // drawing the reference images
  double wallSeconds = 0.0;         // the whole evaluation
};

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
