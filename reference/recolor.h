#pragma once
// The colour of a frame already drawn, under another cache state. A frame's geometry (which
// triangle each pixel shows, its texture coordinates and their quad derivatives) does not depend
// on what the cache holds, and neither does its needbuffer or depth: only the texel lookups do.
// So an evaluation draws each camera view once, with every page resident and the debug channels
// on (that frame is also the reference image), and shades the recorded fragment inputs again
// under each configuration's cache state. The shader function and its inputs are the ones
// renderFrame uses, so the colour is byte-identical to renderFrame(mesh, cache, settings).color
// (tests/reference/recolor_test.cpp), without visibility or plane evaluation.

#include <cstdint>
#include <vector>

#include "reference/cache_state.h"
#include "reference/frame.h"
#include "reference/renderer.h"

namespace vt::reference {

// `drawn`: a frame rendered at `settings`' viewport with RenderSettings::debugChannels set.
// Writes RGBA8 rows bottom to top into `color` (resized). Throws std::invalid_argument when
// `drawn` lacks the debug channels or its viewport is not `settings`'.
void recolor(const Frame& drawn, const CacheState& cache, const RenderSettings& settings,
             std::vector<uint8_t>& color);

}  // namespace vt::reference
