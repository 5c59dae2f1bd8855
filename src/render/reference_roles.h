#pragma once
// The roles only the CPU oracle plays, as the evaluation, the goldens and the retexturing tool ask
// for them (docs/architecture.md, "Renderers to the loop"). A GL context draws what a cache state
// holds, one frame at a time, on its own thread; these draw on any thread without a context:
//   ResidentRenderer   a texture with every stored page resident (on a sparse texture a missing
//                      page's nearest stored ancestor): reference images, the first frame's
//                      needbuffer for an initial cache state, an evaluation's shared views
//   CacheRenderer      a given cache state, and a frame drawn with the debug channels shaded again
//                      under other cache states (the same bytes as drawing each: recolouring)
// src/backends/ makes the oracle's; nothing that asks for a role includes the oracle.

#include <cstdint>
#include <span>
#include <vector>

#include "render/cache_state.h"
#include "render/frame.h"
#include "render/render_settings.h"

namespace vt {

class ResidentRenderer {
 public:
  virtual ~ResidentRenderer() = default;
  // Into `frame`: every pixel of every channel is written, and a frame of the same viewport keeps
  // its buffers.
  virtual void draw(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                    Frame& frame) const = 0;
  Frame draw(const ClipSpaceMesh& mesh, const RenderSettings& settings) const {
    Frame frame;
    draw(mesh, settings, frame);
    return frame;
  }
};

class CacheRenderer {
 public:
  virtual ~CacheRenderer() = default;
  virtual Frame draw(const ClipSpaceMesh& mesh, const CacheState& cache,
                     const RenderSettings& settings) const = 0;
  // `drawn`: a frame drawn at `settings`' viewport with RenderSettings::debugChannels set. Writes
  // RGBA8 rows bottom to top into colors[k] (resized) for caches[k].
  virtual void recolor(const Frame& drawn, std::span<const CacheState* const> caches,
                       const RenderSettings& settings,
                       std::span<std::vector<uint8_t>* const> colors) const = 0;
};

}  // namespace vt
