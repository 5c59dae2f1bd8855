#pragma once
// `vt render`'s work as one call: one frame of a mesh from a camera, drawn by the oracle or the GL
// path from one cache state (the levels asked for, else the levels an 8192^2 cache texture holds,
// coarsest first, whatever the backend; or, for the oracle alone, every stored page read from the
// file), written as a colour image and optionally a needbuffer image coloured by level, with its
// run time and, given a reference image, its RMSE, SSIM and WSSIM against it.

#include <filesystem>
#include <ostream>

#include "backends/backend.h"
#include "format/virtual_texture_reader.h"
#include "render/render_settings.h"
#include "scene/camera.h"
#include "scene/mesh.h"

namespace vt {

struct RenderRequest {
  Mesh mesh;
  Camera camera;
  RenderSettings settings;  // viewport, arithmetic, depth, filters, need8, threads
  Backend backend = Backend::kOracle;
  int residentLevels = -1;  // levels 0..K-1; -1: what a cache texture holds
  bool everyPage = false;   // the oracle only (drawsEveryPage)
  std::filesystem::path output, needbuffer, reference;  // needbuffer, reference: optional
};

void renderOneFrame(const VirtualTextureReader& reader, const RenderRequest& request,
                    std::ostream& out);

}  // namespace vt
