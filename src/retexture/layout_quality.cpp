#include "retexture/layout_quality.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <set>

#include "format/page_address.h"

namespace vt {
namespace {

// Finest-level pages touched by the areas, as (py << 32 | px), sorted.
std::vector<uint64_t> touchedPages(const Retexturing& layout) {
  std::set<uint64_t> pages;
  for (const TextureArea& area : layout.areas) {
    const uint64_t x0 = area.x / layout.pageSize, x1 = (area.x + area.width - 1) / layout.pageSize;
    const uint64_t y0 = area.y / layout.pageSize, y1 = (area.y + area.height - 1) / layout.pageSize;
    for (uint64_t py = y0; py <= y1; ++py)
      for (uint64_t px = x0; px <= x1; ++px) pages.insert(py << 32 | px);
  }
  return {pages.begin(), pages.end()};
}

// The pages and all their ancestors, level by level up to the root.
uint64_t pagesWithAncestors(std::vector<uint64_t> pages, uint64_t pagesPerSide) {
  uint64_t total = 0;
  for (uint64_t n = pagesPerSide;; n /= 2) {
    total += pages.size();
    if (n <= 1) break;
    for (uint64_t& page : pages) page = ((page >> 32) / 2) << 32 | (page & 0xffffffffu) / 2;
    std::sort(pages.begin(), pages.end());
    pages.erase(std::unique(pages.begin(), pages.end()), pages.end());
  }
  return total;
}

// Texels of the area (local coordinates) whose squares overlap a triangle of its faces.
uint64_t referencedTexels(const TexturedScene& scene, const Retexturing& layout,
                          const std::vector<glm::vec2>& uvs, const TextureArea& area,
                          const std::vector<uint32_t>& faces) {
  std::vector<uint8_t> touched(uint64_t{area.width} * area.height, 0);
  const auto side = static_cast<double>(layout.side);
  for (const uint32_t f : faces) {
    const TexturedFace& face = scene.faces[f];
    for (uint32_t t = face.firstIndex; t < face.firstIndex + face.indexCount; t += 3) {
      glm::dvec2 p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = glm::dvec2(uvs[scene.indices[t + k]]) * side -
               glm::dvec2(static_cast<double>(area.x), static_cast<double>(area.y));
      // Edge functions oriented so the inside is >= 0.
      const double orientation =
          (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
      if (orientation == 0.0) continue;  // no area, no texel
      const double sign = orientation < 0.0 ? -1.0 : 1.0;
      const auto clampTo = [](double v, uint32_t n) {
        return static_cast<int64_t>(std::clamp(v, 0.0, static_cast<double>(n)));
      };
      const int64_t x0 = clampTo(std::floor(std::min({p[0].x, p[1].x, p[2].x})), area.width);
      const int64_t x1 = clampTo(std::ceil(std::max({p[0].x, p[1].x, p[2].x})), area.width);
      const int64_t y0 = clampTo(std::floor(std::min({p[0].y, p[1].y, p[2].y})), area.height);
      const int64_t y1 = clampTo(std::ceil(std::max({p[0].y, p[1].y, p[2].y})), area.height);
      for (int64_t y = y0; y < y1; ++y)
        for (int64_t x = x0; x < x1; ++x) {
          bool overlaps = true;
          for (int k = 0; k < 3 && overlaps; ++k) {
            const glm::dvec2 a = p[k], b = p[(k + 1) % 3];
            const glm::dvec2 normal = sign * glm::dvec2(-(b.y - a.y), b.x - a.x);
            // The square's corner furthest along the inward normal.
            const double cx = static_cast<double>(x) + (normal.x > 0.0 ? 1.0 : 0.0);
            const double cy = static_cast<double>(y) + (normal.y > 0.0 ? 1.0 : 0.0);
            overlaps = normal.x * (cx - a.x) + normal.y * (cy - a.y) >= 0.0;
          }
          if (overlaps)
            touched[static_cast<uint64_t>(y) * area.width + static_cast<uint64_t>(x)] = 1;
        }
    }
  }
  return static_cast<uint64_t>(std::count(touched.begin(), touched.end(), uint8_t{1}));
}

}  // namespace

LayoutQuality measureLayout(const TexturedScene& scene, const Retexturing& layout,
                            const std::vector<glm::vec2>& uvs) {
  std::vector<std::vector<uint32_t>> facesOfArea(layout.areas.size());
  for (uint32_t f = 0; f < scene.faces.size(); ++f) facesOfArea[layout.faceArea[f]].push_back(f);
  const std::vector<uint64_t> pages = touchedPages(layout);
  LayoutQuality quality{.finestPages = pages.size(),
                        .allPages = pagesWithAncestors(pages, layout.side / layout.pageSize)};
  quality.referencedTexels = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, layout.areas.size()), uint64_t{0},
      [&](const tbb::blocked_range<size_t>& range, uint64_t sum) {
        for (size_t a = range.begin(); a < range.end(); ++a)
          sum += referencedTexels(scene, layout, uvs, layout.areas[a], facesOfArea[a]);
        return sum;
      },
      std::plus<>());
  quality.referencedFraction =
      static_cast<double>(quality.referencedTexels) /
      (static_cast<double>(quality.finestPages) * layout.pageSize * layout.pageSize);
  return quality;
}

}  // namespace vt
