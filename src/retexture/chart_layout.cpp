#include "retexture/chart_layout.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "common/error.h"
#include "format/texture_description.h"

namespace vt {
namespace {

struct ShelfPosition {
  uint64_t x = 0, y = 0;
};

// Positions for `charts` in `order` on shelves of a side x side texture, or nothing.
std::optional<std::vector<ShelfPosition>> packShelves(const std::vector<Chart>& charts,
                                                      const std::vector<uint32_t>& order,
                                                      uint64_t side) {
  std::vector<ShelfPosition> positions(charts.size());
  uint64_t x = 0, y = 0, shelfHeight = 0;
  for (const uint32_t c : order) {
    const Chart& chart = charts[c];
    if (chart.width() > side) return std::nullopt;
    if (x + chart.width() > side) {
      y += shelfHeight;
      x = 0;
      shelfHeight = 0;
    }
    if (y + chart.height() > side) return std::nullopt;
    positions[c] = {x, y};
    x += chart.width();
    shelfHeight = std::max(shelfHeight, chart.height());
  }
  return positions;
}

// Z-order of each chart's centroid in the scene's bounding box, 21 bits per axis.
std::vector<uint64_t> mortonKeys(const TexturedScene& scene, const std::vector<Chart>& charts) {
  glm::vec3 low(INFINITY), high(-INFINITY);
  for (const glm::vec3& p : scene.positions) low = glm::min(low, p), high = glm::max(high, p);
  const glm::vec3 extent = glm::max(high - low, glm::vec3(1e-30f));
  std::vector<uint64_t> keys;
  for (const Chart& chart : charts) {
    glm::dvec3 sum(0.0);
    uint64_t count = 0;
    for (const uint32_t f : chart.faces) {
      const TexturedFace& face = scene.faces[f];
      for (uint32_t i = face.firstIndex; i < face.firstIndex + face.indexCount; ++i, ++count)
        sum += glm::dvec3(scene.positions[scene.indices[i]]);
    }
    const glm::vec3 unit = (glm::vec3(sum / double(count)) - low) / extent;
    uint64_t key = 0;
    for (int bit = 20; bit >= 0; --bit)
      for (int axis = 0; axis < 3; ++axis) {
        const auto q = static_cast<uint64_t>(std::clamp(unit[axis], 0.0f, 1.0f) * 2097151.0f);
        key = key << 1 | ((q >> bit) & 1u);
      }
    keys.push_back(key);
  }
  return keys;
}

}  // namespace

Retexturing layoutCharts(const TexturedScene& scene, uint32_t pageSize,
                         const ChartOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Chart> charts = buildCharts(scene, options);
  std::vector<uint32_t> order(charts.size());
  std::iota(order.begin(), order.end(), 0u);
  const std::vector<uint64_t> morton = mortonKeys(scene, charts);
  // Shelves hold charts of one height class; inside a class, neighbours in the scene come next
  // to each other (Z-order), so a view's faces share pages.
  const auto heightClass = [&](uint32_t c) { return (charts[c].height() + 15) / 16; };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if (heightClass(a) != heightClass(b)) return heightClass(a) > heightClass(b);
    if (morton[a] != morton[b]) return morton[a] < morton[b];
    return a < b;
  });

  uint64_t texels = 0;
  for (const Chart& chart : charts) texels += chart.width() * chart.height();
  uint32_t level = 0;
  while (levelSide(pageSize, level) * levelSide(pageSize, level) < texels) ++level;
  std::optional<std::vector<ShelfPosition>> positions;
  for (; level <= kMaxLevel; ++level)
    if ((positions = packShelves(charts, order, levelSide(pageSize, level)))) break;
  if (!positions) throw InputError(scene.name, "the charts exceed the format's largest texture");

  Retexturing layout;
  layout.method = "charts";
  layout.pageSize = pageSize;
  layout.side = levelSide(pageSize, level);
  layout.faceArea.resize(scene.faces.size());
  layout.faceShift.resize(scene.faces.size());
  for (size_t c = 0; c < charts.size(); ++c) {
    const Chart& chart = charts[c];
    for (size_t k = 0; k < chart.faces.size(); ++k) {
      layout.faceArea[chart.faces[k]] = static_cast<uint32_t>(layout.areas.size());
      layout.faceShift[chart.faces[k]] = chart.offsets[k];
    }
    layout.areas.push_back({.texture = chart.texture,
                            .sourceX = chart.x0,
                            .sourceY = chart.y0,
                            .x = (*positions)[c].x,
                            .y = (*positions)[c].y,
                            .width = static_cast<uint32_t>(chart.width()),
                            .height = static_cast<uint32_t>(chart.height())});
  }
  layout.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return layout;
}

}  // namespace vt
