#pragma once
// The viewer's HUD as pixels: lines of text in a built-in 5 x 7 pixel font (upper-case letters,
// digits and . : % / - + ( ) and space; lower-case letters are drawn upper-case, anything else
// as a box), white on a black panel, `scale` screen pixels per font pixel. Rows run
// bottom to top, as GL textures and the oracle's frames.

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
