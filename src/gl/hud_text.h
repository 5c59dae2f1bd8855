#pragma once
// The viewer's HUD as pixels: lines of text in the project's 5 x 7 pixel font
// (common/bitmap_font.h; lines 9 font pixels apart, so descenders stay clear of the next line),
// white on a black panel, `scale` screen pixels per font pixel. Rows run bottom to top, as GL
// textures and the oracle's frames.

#include <cstdint>
#include <string>
#include <vector>

namespace vt {

struct HudImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

HudImage renderHudText(const std::vector<std::string>& lines, uint32_t scale);

}  // namespace vt
