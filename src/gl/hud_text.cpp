#include "gl/hud_text.h"

#include <algorithm>
#include <span>

#include "common/bitmap_font.h"

namespace vt {

HudImage renderHudText(const std::vector<std::string>& lines, uint32_t scale) {
  constexpr int kLineHeight = 9, kMargin = 2;  // font pixels
  const int s = static_cast<int>(scale);
  size_t longest = 0;
  for (const std::string& line : lines) longest = std::max(longest, line.size());
  HudImage image;
  image.width = (static_cast<uint32_t>(longest) * kGlyphAdvance + 2 * kMargin) * scale;
  image.height = (static_cast<uint32_t>(lines.size()) * kLineHeight + 2 * kMargin) * scale;
  // Draw top to bottom, as the font does, then flip to the GL's rows bottom to top.
  std::vector<uint8_t> topDown(size_t{image.width} * image.height * 4, 0);
  for (size_t i = 3; i < topDown.size(); i += 4) topDown[i] = 255;  // a black panel
  const RgbaCanvas canvas{static_cast<int>(image.width), static_cast<int>(image.height), topDown};
  for (size_t l = 0; l < lines.size(); ++l)
    drawText(canvas, kMargin * s, (kMargin + static_cast<int>(l) * kLineHeight) * s, lines[l], s,
             {255, 255, 255, 255});
  const size_t rowBytes = size_t{image.width} * 4;
  image.rgba.resize(topDown.size());
  for (uint32_t y = 0; y < image.height; ++y)
    std::copy_n(
        topDown.begin() + static_cast<std::ptrdiff_t>(y * rowBytes), rowBytes,
        image.rgba.begin() + static_cast<std::ptrdiff_t>((image.height - 1 - y) * rowBytes));
  return image;
}

}  // namespace vt
