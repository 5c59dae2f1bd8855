#include "scene/bezier_patch.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace vt {
namespace {

// The quadratic Bernstein polynomials at t: (1-t)^2, 2t(1-t), t^2. At t = 0 and t = 1 they are
// exactly (1, 0, 0) and (0, 0, 1), so patch corners are their control points bit for bit.
glm::dvec3 bernstein(double t) { return {(1 - t) * (1 - t), 2 * t * (1 - t), t * t}; }

// Sums w_row[j] * w_column[i] * control[(row0 + j) * width + column0 + i] over the 3x3 control
// points of one patch, in double, rounded to float once.
template <typename Vec>
Vec evaluate(std::span<const Vec> control, int width, int column0, int row0,
             const glm::dvec3& wColumn, const glm::dvec3& wRow) {
  using DVec = glm::vec<Vec::length(), double>;
  DVec sum(0.0);
  for (int j = 0; j < 3; ++j) {
    DVec rowSum(0.0);
    for (int i = 0; i < 3; ++i)
      rowSum += wColumn[i] * DVec(control[static_cast<size_t>((row0 + j) * width + column0 + i)]);
    sum += wRow[j] * rowSum;
  }
  return Vec(sum);
}

}  // namespace

TessellatedPatch tessellatePatch(std::span<const glm::vec3> positions,
                                 std::span<const glm::vec2> st, int width, int height, int level) {
  if (width < 3 || height < 3 || width % 2 == 0 || height % 2 == 0)
    throw std::invalid_argument("patch control grid " + std::to_string(width) + " x " +
                                std::to_string(height) + " is not (2n+1) x (2m+1) with n, m >= 1");
  if (level < 1) throw std::invalid_argument("patch tessellation level must be at least 1");
  const size_t controlCount = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (positions.size() != controlCount || st.size() != controlCount)
    throw std::invalid_argument("patch has " + std::to_string(positions.size()) +
                                " positions and " + std::to_string(st.size()) + " st for " +
                                std::to_string(controlCount) + " control points");
  // n x m patches along the rows (width) and columns (height).
  const int n = (width - 1) / 2, m = (height - 1) / 2;
  const int64_t columns = int64_t{n} * level + 1, rows = int64_t{m} * level + 1;
  if (columns * rows > int64_t{std::numeric_limits<uint32_t>::max()})
    throw std::invalid_argument("patch tessellation level " + std::to_string(level) +
                                " gives more vertices than 32-bit indices address");

  // Grid vertex (c, r) lies in patch (c / level, r / level) at parameter (c % level) / level; an
  // edge shared by two patches is evaluated once, from the patch after it (the last row and column
  // from the last patch at t = 1), so neighbours share those vertices exactly.
  TessellatedPatch patch;
  patch.positions.reserve(static_cast<size_t>(columns * rows));
  patch.st.reserve(static_cast<size_t>(columns * rows));
  const auto locate = [level](int64_t g, int patches, int& patchIndex) {
    patchIndex = std::min(static_cast<int>(g / level), patches - 1);
    return bernstein(static_cast<double>(g - int64_t{patchIndex} * level) / level);
  };
  for (int64_t r = 0; r < rows; ++r) {
    int py = 0;
    const glm::dvec3 wRow = locate(r, m, py);
    for (int64_t c = 0; c < columns; ++c) {
      int px = 0;
      const glm::dvec3 wColumn = locate(c, n, px);
      patch.positions.push_back(evaluate(positions, width, 2 * px, 2 * py, wColumn, wRow));
      patch.st.push_back(evaluate(st, width, 2 * px, 2 * py, wColumn, wRow));
    }
  }

  // Two triangles per grid cell, in Quake 3's order (RB_SurfaceGrid), with a the cell's first
  // vertex, rows running down the grid:
  //   a --- b      (a, d, b) and (b, d, e)
  //   |   / |
  //   d --- e
  patch.indices.reserve(static_cast<size_t>(6 * (columns - 1) * (rows - 1)));
  for (int64_t r = 0; r + 1 < rows; ++r) {
    for (int64_t c = 0; c + 1 < columns; ++c) {
      const auto a = static_cast<uint32_t>(r * columns + c), b = a + 1;
      const auto d = static_cast<uint32_t>(a + columns), e = d + 1;
      patch.indices.insert(patch.indices.end(), {a, d, b, b, d, e});
    }
  }
  return patch;
}

}  // namespace vt
