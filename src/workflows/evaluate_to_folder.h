#pragma once
// `vt eval`'s work as one call: configurations flown in lockstep over one camera path
// (eval/evaluation.h), refused up front when their caches and frames do not fit in memory, with a
// progress bar, written into the output folder (frames.csv, summary.md/.json and plots:
// eval/evaluation_report.h), and the totals of every run as one line each.

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "common/shard.h"
#include "eval/evaluation_report.h"
#include "eval/flight_configuration.h"
#include "format/virtual_texture_reader.h"
#include "render/arithmetic.h"
#include "scene/camera_path.h"
#include "scene/mesh.h"

namespace vt {

struct EvaluateRequest {
  Mesh mesh;
  CameraPath path;
  std::filesystem::path pathFile;  // for messages: the camera path's file, empty for the default
  std::vector<FlightConfiguration> configurations;
  std::filesystem::path configurationsFile;  // where they came from, empty for lists
  EvaluationDescription description;         // title, scene, texture, figures (jobs: from `jobs`)
  Viewport screen{320, 200};
  Arithmetic arithmetic;
  unsigned jobs = 0;  // runs at once (0: every core)
  std::filesystem::path output;
  // The references' texture when not the flown one (EvaluationOptions::reference).
  const VirtualTextureReader* reference = nullptr;
  // Flies only the configurations this shard takes in turn and writes shard.json besides
  // (eval/evaluation_report.h); no plots, which `vt merge` draws.
  std::optional<Shard> shard = std::nullopt;
};

Evaluation evaluateToFolder(const VirtualTextureReader& reader, EvaluateRequest request,
                            std::ostream& out);

}  // namespace vt
