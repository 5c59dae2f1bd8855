#pragma once
// The CPU oracle: renders a clip-space mesh with a virtual texture exactly as the GL renderer's
// shader does (docs/design.md section 3), multithreaded over tiles, with the same bytes for any
// thread count.
//
// Per pixel: Embree and the GL rules find the shown triangle (visibility.h); its planes are
// evaluated at the four pixels of the pixel's 2x2 quad, helper pixels included (they need not be
// covered), as llvmpipe evaluates them (rule 6): q = fma(dqdy, y, fma(dqdx, x, q0)) and
// attribute = q_a * (1 / q_w). dFdxFine is the right pixel minus the left one in the pixel's quad
// row, dFdyFine the upper minus the lower in its quad column (window y up). The shared shader
// logic (src/shader/virtual_texture.glsl) then computes the LOD, the needbuffer and the colour.

#include "reference/texture_source.h"
#include "render/cache_state.h"
#include "render/frame.h"
#include "render/render_settings.h"

namespace vt::reference {

// Every page resident (golden images): each lookup finds the page itself or, on a sparse
// texture, its nearest stored ancestor.
Frame renderFrame(const ClipSpaceMesh& mesh, const ResidentTexture& texture,
                  const RenderSettings& settings);

// A given cache state, as the GL renderer holds it.
Frame renderFrame(const ClipSpaceMesh& mesh, const CacheState& cache,
                  const RenderSettings& settings);

// The same, into `frame`: every pixel of every channel is written, and a frame of the same
// viewport keeps its buffers (a flight or a benchmark drawing frame after frame allocates once).
void renderFrame(const ClipSpaceMesh& mesh, const ResidentTexture& texture,
                 const RenderSettings& settings, Frame& frame);
void renderFrame(const ClipSpaceMesh& mesh, const CacheState& cache, const RenderSettings& settings,
                 Frame& frame);

}  // namespace vt::reference
