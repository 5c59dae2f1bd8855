#include "retexture/layout_quality.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <set>

#include "common/resource_limits.h"
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

// A triangle of a face in its area's texel coordinates (the area's first texel at the origin).
struct AreaTriangle {
  glm::dvec2 p[3];
  double sign = 1.0;                       // orients the edge functions so that the inside is >= 0
  int64_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // texels [x0, x1) x [y0, y1) of its bounds, clamped

  AreaTriangle(const TexturedScene& scene, const Retexturing& layout,
               const std::vector<glm::vec2>& uvs, const TextureArea& area, uint32_t first) {
    const auto side = static_cast<double>(layout.side);
    for (int k = 0; k < 3; ++k)
      p[k] = glm::dvec2(uvs[scene.indices[first + k]]) * side -
             glm::dvec2(static_cast<double>(area.x), static_cast<double>(area.y));
    const double orientation =
        (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
    if (orientation == 0.0) return;  // no area, no texel: empty bounds
    sign = orientation < 0.0 ? -1.0 : 1.0;
    const auto clampTo = [](double v, uint32_t n) {
      return static_cast<int64_t>(std::clamp(v, 0.0, static_cast<double>(n)));
    };
    x0 = clampTo(std::floor(std::min({p[0].x, p[1].x, p[2].x})), area.width);
    x1 = clampTo(std::ceil(std::max({p[0].x, p[1].x, p[2].x})), area.width);
    y0 = clampTo(std::floor(std::min({p[0].y, p[1].y, p[2].y})), area.height);
    y1 = clampTo(std::ceil(std::max({p[0].y, p[1].y, p[2].y})), area.height);
  }

  // Texel (x, y)'s square overlaps the triangle: inside every edge's half-plane (the bounds test
  // is the rows and columns walked).
  bool overlaps(int64_t x, int64_t y) const {
    for (int k = 0; k < 3; ++k) {
      const glm::dvec2 a = p[k], b = p[(k + 1) % 3];
      const glm::dvec2 normal = sign * glm::dvec2(-(b.y - a.y), b.x - a.x);
      // The square's corner furthest along the inward normal.
      const double cx = static_cast<double>(x) + (normal.x > 0.0 ? 1.0 : 0.0);
      const double cy = static_cast<double>(y) + (normal.y > 0.0 ? 1.0 : 0.0);
      if (normal.x * (cx - a.x) + normal.y * (cy - a.y) < 0.0) return false;
    }
    return true;
  }

  // The texels of row y that overlap, [first, last] (empty when first > last). A row of a convex
  // triangle overlaps one run of texels: the x-extent of the triangle within the row's strip
  // [y, y + 1] gives it; the texel test then settles the run's ends exactly as it would texel by
  // texel.
  std::pair<int64_t, int64_t> run(int64_t y) const {
    double lo = 1e300, hi = -1e300;
    const auto extend = [&](double x) { lo = std::min(lo, x), hi = std::max(hi, x); };
    const auto top = static_cast<double>(y), bottom = top + 1.0;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec2 a = p[k], b = p[(k + 1) % 3];
      if (a.y >= top && a.y <= bottom) extend(a.x);
      for (const double line : {top, bottom})
        if ((a.y - line) * (b.y - line) < 0.0)
          extend(a.x + (line - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    if (lo > hi) return {1, 0};
    int64_t first = std::max(x0, static_cast<int64_t>(std::ceil(lo)) - 1);
    int64_t last = std::min(x1 - 1, static_cast<int64_t>(std::floor(hi)));
    while (first > x0 && overlaps(first - 1, y)) --first;
    while (first <= last && !overlaps(first, y)) ++first;
    while (last < x1 - 1 && overlaps(last + 1, y)) ++last;
    while (last >= first && !overlaps(last, y)) --last;
    return {first, last};
  }
};

// Texels of the area (local coordinates) whose squares overlap a triangle of its faces, counted
// row by row: the runs of the triangles that span a row, merged where they meet. Work grows with
// the rows the triangles span and memory with the triangles, never with the texels of the area
// (an image header may claim 65535^2 of them).
uint64_t referencedTexels(const TexturedScene& scene, const Retexturing& layout,
                          const std::vector<glm::vec2>& uvs, const TextureArea& area,
                          const std::vector<uint32_t>& faces) {
  std::vector<AreaTriangle> triangles;
  for (const uint32_t f : faces) {
    const TexturedFace& face = scene.faces[f];
    for (uint32_t t = face.firstIndex; t < face.firstIndex + face.indexCount; t += 3) {
      AreaTriangle triangle(scene, layout, uvs, area, t);
      if (triangle.y0 < triangle.y1) triangles.push_back(triangle);
    }
  }
  std::sort(triangles.begin(), triangles.end(),
            [](const AreaTriangle& a, const AreaTriangle& b) { return a.y0 < b.y0; });
  uint64_t texels = 0;
  std::vector<const AreaTriangle*> spanning;  // the triangles that span row y
  std::vector<std::pair<int64_t, int64_t>> runs;
  size_t next = 0;
  for (int64_t y = 0; next < triangles.size() || !spanning.empty(); ++y) {
    if (spanning.empty()) y = std::max(y, triangles[next].y0);  // skip rows no triangle spans
    for (; next < triangles.size() && triangles[next].y0 <= y; ++next)
      spanning.push_back(&triangles[next]);
    runs.clear();
    for (const AreaTriangle* triangle : spanning) {
      const auto run = triangle->run(y);
      if (run.first <= run.second) runs.push_back(run);
    }
    std::sort(runs.begin(), runs.end());
    for (size_t i = 0; i < runs.size();) {
      auto [first, last] = runs[i];
      for (++i; i < runs.size() && runs[i].first <= last + 1; ++i)
        last = std::max(last, runs[i].second);
      texels += static_cast<uint64_t>(last - first + 1);
    }
    std::erase_if(spanning, [y](const AreaTriangle* triangle) { return triangle->y1 <= y + 1; });
  }
  return texels;
}

// The texel rows that referencedTexels walks for every area: each triangle's rows.
uint64_t coverageRows(const TexturedScene& scene, const Retexturing& layout,
                      const std::vector<glm::vec2>& uvs) {
  uint64_t rows = 0;
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const TexturedFace& face = scene.faces[f];
    const TextureArea& area = layout.areas[layout.faceArea[f]];
    for (uint32_t t = face.firstIndex; t < face.firstIndex + face.indexCount; t += 3) {
      const AreaTriangle triangle(scene, layout, uvs, area, t);
      rows += static_cast<uint64_t>(triangle.y1 - triangle.y0);
    }
  }
  return rows;
}

}  // namespace

LayoutQuality measureLayout(const TexturedScene& scene, const Retexturing& layout,
                            const std::vector<glm::vec2>& uvs) {
  std::vector<std::vector<uint32_t>> facesOfArea(layout.areas.size());
  for (uint32_t f = 0; f < scene.faces.size(); ++f) facesOfArea[layout.faceArea[f]].push_back(f);
  // The rows bound the work of measuring the referenced texels: refused before it starts.
  const uint64_t rows = coverageRows(scene, layout, uvs);
  if (rows > kMaxCoverageRows)
    throw limitError(describedSource(scene),
                     "measuring the texels its faces reference (a run of texels in each texel "
                     "row of each triangle, " +
                         layout.method + " layout)",
                     rows, kMaxCoverageRows, " rows");
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
