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

// Shelves in the band of columns [left, left + width), rows [top, bottom): a chart goes onto the
// first open shelf that is tall enough and has room left, else onto a new shelf below the last.
class Shelves {
 public:
  Shelves(uint64_t left, uint64_t width, uint64_t top, uint64_t bottom)
      : left_(left), width_(width), bottom_(bottom), next_(top) {}

  std::optional<ShelfPosition> place(const Chart& chart) {
    if (chart.width() > width_) return std::nullopt;
    for (Shelf& shelf : shelves_)
      if (chart.height() <= shelf.height && shelf.used + chart.width() <= width_) {
        const ShelfPosition at{left_ + shelf.used, shelf.y};
        shelf.used += chart.width();
        return at;
      }
    if (next_ + chart.height() > bottom_) return std::nullopt;
    shelves_.push_back({next_, chart.height(), chart.width()});
    next_ += chart.height();
    return ShelfPosition{left_, shelves_.back().y};
  }
  uint64_t end() const { return next_; }

 private:
  struct Shelf {
    uint64_t y, height, used;
  };
  uint64_t left_, width_, bottom_, next_;
  std::vector<Shelf> shelves_;
};

// Wide charts on shelves across the texture at the top, then the narrow ones on shelves within
// columns of `column` texels below them, column after column.
std::optional<std::vector<ShelfPosition>> pack(const std::vector<Chart>& charts,
                                               const std::vector<uint32_t>& wide,
                                               const std::vector<uint32_t>& narrow, uint64_t side,
                                               uint64_t column) {
  std::vector<ShelfPosition> positions(charts.size());
  Shelves top(0, side, 0, side);
  for (const uint32_t c : wide) {
    const auto at = top.place(charts[c]);
    if (!at) return std::nullopt;
    positions[c] = *at;
  }
  column = std::min(column, side);
  uint64_t left = 0;
  Shelves shelves(left, column, top.end(), side);
  for (const uint32_t c : narrow) {
    auto at = shelves.place(charts[c]);
    if (!at) {
      left += column;
      if (left + column > side) return std::nullopt;
      shelves = Shelves(left, column, top.end(), side);
      if (!(at = shelves.place(charts[c]))) return std::nullopt;
    }
    positions[c] = *at;
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
  const std::vector<uint64_t> morton = mortonKeys(scene, charts);
  // Narrow charts in Z-order of the scene, so that faces near each other in the scene land in
  // one column, near each other: at coarser levels, where a page spans several charts, a view's
  // faces share pages. Wide charts by height class (16 texels) first, then Z-order.
  const uint64_t column = uint64_t{options.columnPages} * pageSize;
  std::vector<uint32_t> wide, narrow;
  for (uint32_t c = 0; c < charts.size(); ++c)
    (charts[c].width() > column ? wide : narrow).push_back(c);
  const auto heightClass = [&](uint32_t c) { return (charts[c].height() + 15) / 16; };
  std::sort(wide.begin(), wide.end(), [&](uint32_t a, uint32_t b) {
    if (heightClass(a) != heightClass(b)) return heightClass(a) > heightClass(b);
    if (morton[a] != morton[b]) return morton[a] < morton[b];
    return a < b;
  });
  std::sort(narrow.begin(), narrow.end(), [&](uint32_t a, uint32_t b) {
    return morton[a] != morton[b] ? morton[a] < morton[b] : a < b;
  });

  uint64_t texels = 0;
  for (const Chart& chart : charts) texels += chart.width() * chart.height();
  uint32_t level = 0;
  while (levelSide(pageSize, level) * levelSide(pageSize, level) < texels) ++level;
  std::optional<std::vector<ShelfPosition>> positions;
  for (; level <= kMaxLevel; ++level)
    if ((positions = pack(charts, wide, narrow, levelSide(pageSize, level), column))) break;
  if (!positions)
    throw InputError(describedSource(scene), "the charts exceed the format's largest texture");

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
