#pragma once
// Captures (reference/validate-your-renderer.md, format version 1) written without an image
// library: colour and an 8-bit needbuffer as raw `.rgba8` files, a 32-bit needbuffer as `.need.u32`,
// geometry as `.vertices.f32` and `.indices.u32`, every data file written before the manifest.
// What `vt-capture` writes on a machine where the oracle is not installed; `vt crosscheck
// --captures` reads it like any capture.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "render/cache_state.h"
#include "render/frame.h"
#include "scene/clip_space_mesh.h"

namespace vt::capture {

struct CapturedFrame {
  std::string renderer;     // GL_RENDERER
  std::string textureFile;  // as the manifest names it: relative to its folder, or absolute
  uint64_t textureIdentity = 0;
  const ClipSpaceMesh* mesh = nullptr;
  const CacheState* cache = nullptr;  // as the frame was drawn
  bool need8 = false, trilinear = true, exactFilter = true;
  const Frame* frame = nullptr;  // colour and needbuffer, rows bottom to top
  nlohmann::json extra;          // recorded under "extra" (GL_VERSION, timings, ...)
};

// Writes `frame` as `manifest` (path ending in .json) with its data files next to it.
void writeCapturedFrame(const std::filesystem::path& manifest, const CapturedFrame& frame);

}  // namespace vt::capture
