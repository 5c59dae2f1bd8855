#pragma once
// Golden images: a flight's frames recorded once and checked later (docs/design.md section 5). A
// golden set is a folder:
//   golden.json      the manifest (golden_manifest.h): what was flown and per recorded frame the
//                    checksums of its colour and needbuffer with its RMSE, SSIM and WSSIM
//   frameNNNN.png    each recorded frame's colour, small, for people to look at
// Checking (checkGolden below) flies the same configuration again and compares each recorded
// frame.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/shard.h"
#include "eval/flight.h"
#include "render/arithmetic_points.h"
#include "render/precision_model.h"

namespace vt {

struct GoldenRequest {
  std::filesystem::path texture, mesh, path;  // the mesh and path files must exist
  FlightConfiguration configuration;
  Viewport viewport{160, 100};
  Arithmetic profile = arithmeticPoint("exact");
  int every = 25;  // record frames 0, every, 2 every, ...
};

// Flies and writes the golden set into `folder` (every file through a temporary name).
void generateGolden(const GoldenRequest& request, const std::filesystem::path& folder);

struct GoldenFrameCheck {
  int frame = 0;
  bool colorMatches = false, needMatches = false, qualityMatches = false;
  uint64_t pixelsDiffering = 0;  // against the golden PNG
  int maxColorDifference = 0;    // 8-bit units
  // Under a model with free parameters (a GL implementation other than llvmpipe): the GL frame
  // against the oracle's result sets for the same cache state (frame_comparison.h).
  uint64_t explained = 0, unexplained = 0, ambiguous = 0;
  bool passed = false;
};

struct GoldenCheck {
  std::string backend;
  Arithmetic profile = arithmeticPoint("exact");
  std::string model;  // the model that judged
  std::vector<GoldenFrameCheck> frames;
  bool passed() const;
};

// Flies the golden's flight again with `backend` (GL: a current context is the caller's) in the
// arithmetic of `model` and compares. The texture, mesh and path files are the golden's unless
// given; they must be the same by identity and checksum (InputError otherwise). Without a model
// (the oracle under auto: it draws whatever arithmetic it is given) the flight takes the golden
// set's own profile. Under a pinned model, or none, every recorded frame must match bit for bit;
// under a model with free parameters (gl45, a model file) each recorded frame is judged by the
// oracle's result sets for its cache state, and must leave no pixel unexplained. Writes, for each
// failed frame, frameNNNN.difference.png (colour difference x 16) into `report` with check.json.
// With `shard`, checks only its contiguous block of the recorded frames, flies no further than the
// last of them, and writes shard.json besides (eval/golden_report.h).
GoldenCheck checkGolden(const std::filesystem::path& folder, const std::filesystem::path& texture,
                        const std::filesystem::path& mesh, const std::filesystem::path& path,
                        Backend backend, const std::optional<PrecisionModel>& model,
                        const std::filesystem::path& report,
                        const std::optional<Shard>& shard = std::nullopt);

}  // namespace vt
