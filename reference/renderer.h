#pragma once
// The CPU oracle: renders a clip-space mesh with a virtual texture exactly as the GL renderer's
// shader does (DESIGN section 3), multithreaded over tiles, with the same bytes for any thread
// count.
//
// Per pixel: Embree and the GL rules find the shown triangle (visibility.h); its planes are
// evaluated at the four pixels of the pixel's 2x2 quad, helper pixels included (they need not be
// covered), as llvmpipe evaluates them (rule 6): q = fma(dqdy, y, fma(dqdx, x, q0)) and
// attribute = q_a * (1 / q_w). dFdxFine is the right pixel minus the left one in the pixel's quad
// row, dFdyFine the upper minus the lower in its quad column (window y up). The shared shader
// logic (src/shader/virtual_texture.glsl) then computes the LOD, the needbuffer and the colour.

#include <glm/glm.hpp>
#include <memory>

#include "reference/cache_state.h"
#include "reference/frame.h"
#include "reference/precision_model.h"
#include "reference/precision_profile.h"
#include "reference/texture_source.h"
#include "reference/visibility.h"
#include "shader/needbuffer.h"

namespace vt::reference {

struct RenderSettings {
  Viewport viewport{640, 360};
  PrecisionProfile profile = PrecisionProfile::kExact;  // the oracle's arithmetic
  // The model the frame will be judged under (precision_model.h); its arithmetic must be
  // `profile`. When it leaves any parameter free the frame carries every pixel's result set.
  std::shared_ptr<const PrecisionModel> model = nullptr;
  DepthFormat depthFormat = DepthFormat::kDepth32F;
  bool trilinear = true;
  bool exactFilter = true;  // texel fetches and float filtering; false: the sampler's GL_LINEAR
  bool need8 = false;       // 8-bit needbuffer (textures up to 4096 pages per side)
  // A reduced needbuffer: the viewport is 1/2^k of the screen per axis, and the LOD compensates
  // (virtual_texture_types.glsl). 0: full resolution.
  int needScaleLog2 = 0;
  bool debugChannels = false;  // also fill Frame's uv, derivatives, lod and residentLevel
  // The needbuffer and depth only (a LookAhead camera's pass): no texel is read, the colour is
  // left (0, 0, 0, 0). The needbuffer is the same as with colour: it does not depend on texels.
  bool needOnly = false;
  unsigned threads = 0;        // 0: every core
};

using vt::needClearValue;

// Settings for rendering under `model`: its arithmetic and the model itself.
void applyModel(RenderSettings& settings, const PrecisionModel& model);

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
