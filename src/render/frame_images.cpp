#include "render/frame_images.h"

#include <array>

#include "common/level_hues.h"

namespace vt {
namespace {

size_t flippedIndex(const Frame& frame, int px, int imageRow) {
  const int py = frame.viewport.height - 1 - imageRow;
  return static_cast<size_t>(py) * static_cast<size_t>(frame.viewport.width) +
         static_cast<size_t>(px);
}

}  // namespace

std::vector<uint8_t> colorImage(const Frame& frame) {
  std::vector<uint8_t> image(frame.color.size());
  for (int row = 0; row < frame.viewport.height; ++row)
    for (int px = 0; px < frame.viewport.width; ++px) {
      const size_t from = flippedIndex(frame, px, row) * 4;
      const size_t to = (static_cast<size_t>(row) * static_cast<size_t>(frame.viewport.width) +
                         static_cast<size_t>(px)) *
                        4;
      for (size_t c = 0; c < 4; ++c) image[to + c] = frame.color[from + c];
    }
  return image;
}

std::vector<uint8_t> needImage(const Frame& frame, bool need8) {
  std::vector<uint8_t> image(frame.need.size() * 4, 0);
  for (int row = 0; row < frame.viewport.height; ++row)
    for (int px = 0; px < frame.viewport.width; ++px) {
      const auto page = decodeNeed(frame.need[flippedIndex(frame, px, row)], need8);
      uint8_t* out =
          image.data() + (static_cast<size_t>(row) * static_cast<size_t>(frame.viewport.width) +
                          static_cast<size_t>(px)) *
                             4;
      out[3] = 255;
      if (!page) continue;
      const auto& hue = levelHue(page->level);
      const bool dark = ((page->x + page->y) & 1) != 0;
      for (size_t c = 0; c < 3; ++c) out[c] = static_cast<uint8_t>(dark ? hue[c] * 3 / 5 : hue[c]);
    }
  return image;
}

}  // namespace vt
