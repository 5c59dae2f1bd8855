#pragma once
// The images the frame-by-frame viewer shows besides the rendered frame and its reference (rows
// top to bottom, RGBA8; frames arrive rows bottom to top, as rendered):
//   difference     per pixel the largest colour channel difference d, as a heat ramp: black
//                  (0), through red and yellow, to white (d >= 32 of 255)
//   needbuffer     the needed page's level as a hue, alternate pages darker (reference's
//                  needImage), black where no geometry
//   resident       the level the cache resolves each needed page to (its indirection entry: the
//                  page or its best resident ancestor), same hues; the shader samples that level
//   cache atlas    the cache texture, shrunk by whole factors to at most `maxSide` pixels a side,
//                  with each frame's outline in its resident page's level hue
//   A against B    where two configurations' frames differ from the reference by different
//                  amounts: green where A is nearer (brighter by how much, over 0..32 of 255 in
//                  the largest channel difference), magenta where B is, black where they tie

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "eval/inspect_page.h"
#include "render/cache_state.h"
#include "render/frame.h"

namespace vt {

InspectImage rgbaImage(const char* name, Viewport viewport, std::span<const uint8_t> rgba);
InspectImage differenceImage(Viewport viewport, std::span<const uint8_t> got,
                             std::span<const uint8_t> want);
InspectImage needbufferImage(Viewport viewport, std::span<const glm::uvec4> need, bool need8);
InspectImage residentLevelImage(Viewport viewport, std::span<const glm::uvec4> need, bool need8,
                                const CacheState& cache);
InspectImage cacheAtlasImage(const CacheState& cache, int maxSide);
InspectImage comparisonImage(const std::string& name, Viewport viewport, std::span<const uint8_t> a,
                             std::span<const uint8_t> b, std::span<const uint8_t> want);

}  // namespace vt
