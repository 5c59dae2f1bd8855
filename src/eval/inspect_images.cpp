#include "eval/inspect_images.h"

#include <algorithm>

#include "common/level_hues.h"
#include "format/page_address.h"
#include "render/frame_images.h"

namespace vt {
namespace {

// Row `row` from the top of a frame whose rows run bottom to top.
size_t flippedRow(Viewport viewport, int row) {
  return static_cast<size_t>(viewport.height - 1 - row) * static_cast<size_t>(viewport.width);
}

}  // namespace

InspectImage rgbaImage(const char* name, Viewport viewport, std::span<const uint8_t> rgba) {
  InspectImage image{name, viewport.width, viewport.height, {}};
  image.rgba.resize(rgba.size());
  const size_t stride = static_cast<size_t>(viewport.width) * 4;
  for (int row = 0; row < viewport.height; ++row)
    std::copy_n(rgba.begin() + static_cast<std::ptrdiff_t>(flippedRow(viewport, row) * 4), stride,
                image.rgba.begin() + static_cast<std::ptrdiff_t>(row * stride));
  return image;
}

InspectImage differenceImage(Viewport viewport, std::span<const uint8_t> got,
                             std::span<const uint8_t> want) {
  InspectImage image{"difference", viewport.width, viewport.height, {}};
  image.rgba.assign(static_cast<size_t>(viewport.width) * viewport.height * 4, 255);
  for (int row = 0; row < viewport.height; ++row)
    for (int x = 0; x < viewport.width; ++x) {
      const size_t from = (flippedRow(viewport, row) + static_cast<size_t>(x)) * 4;
      int d = 0;
      for (size_t c = 0; c < 3; ++c)
        d = std::max(d, std::abs(int{got[from + c]} - int{want[from + c]}));
      // Heat ramp over 0..32: red rises first, then green, then blue.
      const double t = std::min(1.0, d / 32.0) * 3.0;
      uint8_t* out = image.rgba.data() + (static_cast<size_t>(row) * viewport.width + x) * 4;
      out[0] = static_cast<uint8_t>(255.0 * std::clamp(t, 0.0, 1.0));
      out[1] = static_cast<uint8_t>(255.0 * std::clamp(t - 1.0, 0.0, 1.0));
      out[2] = static_cast<uint8_t>(255.0 * std::clamp(t - 2.0, 0.0, 1.0));
    }
  return image;
}

InspectImage comparisonImage(const std::string& name, Viewport viewport, std::span<const uint8_t> a,
                             std::span<const uint8_t> b, std::span<const uint8_t> want) {
  InspectImage image{name, viewport.width, viewport.height, {}};
  image.rgba.assign(static_cast<size_t>(viewport.width) * viewport.height * 4, 255);
  for (int row = 0; row < viewport.height; ++row)
    for (int x = 0; x < viewport.width; ++x) {
      const size_t from = (flippedRow(viewport, row) + static_cast<size_t>(x)) * 4;
      int da = 0, db = 0;
      for (size_t c = 0; c < 3; ++c) {
        da = std::max(da, std::abs(int{a[from + c]} - int{want[from + c]}));
        db = std::max(db, std::abs(int{b[from + c]} - int{want[from + c]}));
      }
      const auto level = static_cast<uint8_t>(255.0 * std::min(1.0, std::abs(da - db) / 32.0));
      uint8_t* out = image.rgba.data() + (static_cast<size_t>(row) * viewport.width + x) * 4;
      out[0] = da > db ? level : 0;  // B nearer: magenta
      out[1] = da < db ? level : 0;  // A nearer: green
      out[2] = da > db ? level : 0;
    }
  return image;
}

InspectImage needbufferImage(Viewport viewport, std::span<const glm::uvec4> need, bool need8) {
  Frame frame;
  frame.viewport = viewport;
  frame.need.assign(need.begin(), need.end());
  return {"needbuffer (level)", viewport.width, viewport.height, needImage(frame, need8)};
}

InspectImage residentLevelImage(Viewport viewport, std::span<const glm::uvec4> need, bool need8,
                                const CacheState& cache) {
  InspectImage image{"resident level", viewport.width, viewport.height, {}};
  image.rgba.assign(static_cast<size_t>(viewport.width) * viewport.height * 4, 0);
  for (int row = 0; row < viewport.height; ++row)
    for (int x = 0; x < viewport.width; ++x) {
      uint8_t* out = image.rgba.data() + (static_cast<size_t>(row) * viewport.width + x) * 4;
      out[3] = 255;
      const auto page = decodeNeed(need[flippedRow(viewport, row) + static_cast<size_t>(x)], need8);
      if (!page || page->level >= cache.indirection.levelCount()) continue;
      const auto& hue = levelHue(cache.indirection.entry(*page).z);
      std::copy(hue.begin(), hue.end(), out);
    }
  return image;
}

InspectImage cacheAtlasImage(const CacheState& cache, int maxSide) {
  const uint32_t side = std::max(cache.widthTexels, cache.heightTexels);
  const uint32_t shrink = std::max<uint32_t>(
      1, (side + static_cast<uint32_t>(maxSide) - 1) / static_cast<uint32_t>(maxSide));
  const int width = static_cast<int>(cache.widthTexels / shrink),
            height = static_cast<int>(cache.heightTexels / shrink);
  InspectImage image{"cache atlas", width, height, {}};
  image.rgba.assign(static_cast<size_t>(width) * height * 4, 0);
  // Texel rows of the cache run with t; the image shows frame (0, 0) at the top left.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t from =
          (static_cast<size_t>(y) * shrink * cache.widthTexels + static_cast<size_t>(x) * shrink) *
          4;
      std::copy_n(cache.texels.begin() + static_cast<std::ptrdiff_t>(from), 4,
                  image.rgba.begin() + (static_cast<std::ptrdiff_t>(y) * width + x) * 4);
    }
  const uint32_t frameSide = cache.description.pageSize + 2 * cache.description.border;
  // Frame outlines in the hue of the resident page's level.
  for (const uint64_t page : cache.residentPages) {
    // A resident page's own indirection entry names its frame.
    const PageId id = fromAbsoluteIndex(page);
    const auto& hue = levelHue(id.level);
    const uint32_t fx = cache.indirection.entry(id).x, fy = cache.indirection.entry(id).y;
    const int x0 = static_cast<int>(fx * frameSide / shrink),
              y0 = static_cast<int>(fy * frameSide / shrink),
              x1 = std::min(width, static_cast<int>((fx + 1) * frameSide / shrink)) - 1,
              y1 = std::min(height, static_cast<int>((fy + 1) * frameSide / shrink)) - 1;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        if (x == x0 || x == x1 || y == y0 || y == y1) {
          uint8_t* out = image.rgba.data() + (static_cast<size_t>(y) * width + x) * 4;
          std::copy(hue.begin(), hue.end(), out);
          out[3] = 255;
        }
  }
  return image;
}

}  // namespace vt
