#pragma once
// vt crosscheck TEXTURE: views (the named test scenes, or frames of a flythrough) drawn by the
// oracle, through its public API (<vt/oracle.h>), and by this machine's OpenGL implementation from
// the same cache state, then compared pixel by pixel under a precision model.

#include <filesystem>
#include <string>
#include <vector>

#include "render/render_settings.h"
#include "scene/camera_path.h"
#include "scene/test_scenes.h"
#include "verify/comparison_report.h"

namespace vt {

struct ScenesCheckOptions {
  std::filesystem::path texture;
  std::vector<NamedScene> views;
  Viewport viewport;
  // exact, llvmpipe, gl45, a model file (.json), or auto: a measured model of GL_RENDERER
  // ($VT_PRECISION_MODELS), else the shipped model for it (llvmpipe with FMA, else gl45).
  std::string model = "auto";
  // Receives summary.json and each comparison's difference images, complete or not at all: the
  // report is written into a temporary folder that replaces `output` at the end.
  std::filesystem::path output;
  // Result sets for every pixel, not only where GL's frame differs: the ambiguous fraction and set
  // widths of whole frames (comparison_report.h), at the sets' full cost.
  bool allSets = false;
};

struct ScenesCheck {
  std::string renderer, version, model;
  ComparisonTotals totals;
  bool passed() const { return totals.unexplained == 0; }
};

// Draws every view in two modes (texelFetch with manual trilinear filtering and a 32-bit
// needbuffer; GL_LINEAR bilinear with an 8-bit needbuffer where the texture's levels fit its
// encoding) from the cache of every stored page, or the coarsest levels that fit an 8192^2
// texture. Prints one line per comparison. Pins LP_NUM_THREADS to 2 unless it is set, since
// llvmpipe's results depend on it; the summary records it with the other settings that do.
ScenesCheck crosscheckScenes(const ScenesCheckOptions& options);

}  // namespace vt
