#pragma once
// How a frame is drawn, whichever renderer draws it (render/frame_renderer.h): the viewport, the
// shader's switches (virtual_texture_types.glsl) and, for the oracle, the arithmetic and the
// precision model the frame will be judged under.

#include <cstdint>
#include <memory>
#include <span>

#include "render/arithmetic.h"
#include "render/precision_model.h"
#include "scene/clip_space_mesh.h"

namespace vt {

enum class DepthFormat { kDepth24, kDepth32F };

struct RenderSettings {
  Viewport viewport{640, 360};
  Arithmetic arithmetic;  // the oracle's arithmetic (arithmetic.h); the default is IEEE float
  // The model the frame will be judged under (precision_model.h); its arithmetic must be
  // `arithmetic`. When it leaves any parameter free the frame carries every pixel's result set.
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
  unsigned threads = 0;  // the oracle's worker threads; 0: every core
  // The oracle shades one pixel at a time even where the CPU runs eight in SIMD lanes (AVX2): the
  // same bits either way (tests compare them), slower.
  bool scalarShading = false;
  // Another renderer's frame of the same scene, known before the oracle draws (a capture, or a
  // frame drawn first), to be judged under `model` (frame_comparison.h): result sets are built
  // only for the pixels where its colour or needbuffer differs from the oracle's own value, the
  // pixels that are not identical; the others need none (result_set.h). Rows as the oracle's,
  // the needbuffer in its encoding; not owned. Empty: every pixel's set.
  struct JudgedFrame {
    std::span<const uint8_t> color;  // RGBA8
    std::span<const uint32_t> need;  // four per pixel
    bool empty() const { return need.empty(); }
  };
  JudgedFrame judged;
};

// Settings for rendering under `model`: its arithmetic and the model itself.
void applyModel(RenderSettings& settings, const PrecisionModel& model);

}  // namespace vt
