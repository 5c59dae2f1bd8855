#pragma once
// The colour of a frame already drawn, under other cache states. A frame's geometry (which
// triangle each pixel shows, its texture coordinates and their quad derivatives) does not depend
// on what the cache holds, and neither does its needbuffer or depth: only the texel lookups do.
// So an evaluation draws each camera view once, with every page resident and the debug channels
// on (that frame is also the reference image), and shades the recorded fragment inputs again
// under each configuration's cache state. The shader function and its inputs are the ones
// renderFrame uses, so each colour is byte-identical to renderFrame(mesh, cache, settings).color
// (tests/reference/recolor_test.cpp), without visibility or plane evaluation.
//
// A pixel reads the indirection table at one or two addresses (the pages under it at the levels
// it samples) and texels of the frames those entries name, within the frame: a bordered page's
// footprint reaches one texel beyond the page, so borders of at least one texel keep it inside.
// Two cache states of the same size that read the same pages there with the same filter inputs
// (the footprint relative to the frame and the fractions, which depend on where the frame lies
// only through the rounding of its texel position) give the pixel the same colour, so recolor()
// shades it once for all of them.

#include <cstdint>
#include <span>
#include <vector>

#include "reference/renderer.h"
#include "render/cache_state.h"
#include "render/frame.h"

namespace vt::reference {

// `drawn`: a frame rendered at `settings`' viewport with RenderSettings::debugChannels set, of
// the texture every cache state holds pages of. Writes RGBA8 rows bottom to top into colors[k]
// (resized) for caches[k]. Throws std::invalid_argument when `drawn` lacks the debug channels or
// its viewport is not `settings`', or the spans differ in length.
void recolor(const Frame& drawn, std::span<const CacheState* const> caches,
             const RenderSettings& settings, std::span<std::vector<uint8_t>* const> colors);

// One cache state.
void recolor(const Frame& drawn, const CacheState& cache, const RenderSettings& settings,
             std::vector<uint8_t>& color);

// The pixels listed (indices py * width + px) of `drawn` under one cache state, one thread: their
// RGBA8 into rgba[4 k .. 4 k + 3] for pixels[k], the bytes recolor() writes there. For trying
// many small changes of a cache state (eval/selection_ceiling.h). Throws as recolor() does, and
// std::invalid_argument when a pixel lies outside the frame or `rgba` is not 4 per pixel.
void recolorPixels(const Frame& drawn, const CacheState& cache, const RenderSettings& settings,
                   std::span<const uint32_t> pixels, std::span<uint8_t> rgba);

// The pages a pixel's colour reads through the indirection table (vtShadeFragment): with
// trilinear filtering the pages under it at levels floor(lod) and the next finer one, else the
// needed level's page twice. Pixels without geometry read none (`covered` false).
struct PagesRead {
  PageId first, second;
  bool covered = false;
  bool operator==(const PagesRead&) const = default;
};
// For every pixel of `drawn` (drawn with debug channels at settings' viewport); what a pixel
// reads does not depend on what the cache holds, only on the texture's description and settings.
std::vector<PagesRead> pagesRead(const Frame& drawn, const TextureDescription& description,
                                 const RenderSettings& settings);

}  // namespace vt::reference
