#include "retexture/face_charts.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "common/resource_limits.h"

namespace vt {
namespace {

// Positions compared by their bit patterns: faces of a map that meet repeat the same floats.
using PositionBits = std::array<uint32_t, 3>;

PositionBits positionBits(glm::vec3 p) {
  return {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y), std::bit_cast<uint32_t>(p.z)};
}

uint64_t area(const Chart& chart) { return chart.width() * chart.height(); }

// The texture mapping of a face's first triangle with non-zero area, as a function of position.
struct PlaneMapping {
  glm::dvec3 origin{0.0}, e1{0.0}, e2{0.0}, normal{0.0};
  glm::dvec2 uv0{0.0}, uv1{0.0}, uv2{0.0};
  bool valid = false;
};

PlaneMapping planeMapping(const TexturedScene& scene, const TexturedFace& face) {
  PlaneMapping m;
  for (uint32_t t = face.firstIndex; t < face.firstIndex + face.indexCount && !m.valid; t += 3) {
    const uint32_t a = scene.indices[t], b = scene.indices[t + 1], c = scene.indices[t + 2];
    m.origin = scene.positions[a];
    m.e1 = glm::dvec3(scene.positions[b]) - m.origin;
    m.e2 = glm::dvec3(scene.positions[c]) - m.origin;
    m.normal = glm::cross(m.e1, m.e2);
    m.valid = glm::length(m.normal) > 0.0;
    m.uv0 = scene.uvs[a], m.uv1 = scene.uvs[b], m.uv2 = scene.uvs[c];
  }
  return m;
}

// The whole repetitions (ds, dt) to add to `face`'s coordinates so that it lies in the plane of
// `m` with the same affine texture map (to 1/100 texel): its texels then continue the other
// face's without a seam. Map compilers keep each surface's coordinates near zero by subtracting
// whole repetitions, so neighbours on one plane often differ by such a shift.
std::optional<glm::i64vec2> repetitionShift(const TexturedScene& scene, const PlaneMapping& m,
                                            const TexturedFace& face) {
  if (!m.valid) return std::nullopt;
  const glm::dvec2 texels(scene.textures[face.texture].width, scene.textures[face.texture].height);
  const double normalLength = glm::length(m.normal);
  const double size = std::sqrt(normalLength);
  std::optional<glm::dvec2> shift;
  for (uint32_t i = face.firstIndex; i < face.firstIndex + face.indexCount; ++i) {
    const uint32_t v = scene.indices[i];
    const glm::dvec3 d = glm::dvec3(scene.positions[v]) - m.origin;
    if (std::abs(glm::dot(d, m.normal)) / normalLength > 1e-4 * size) return std::nullopt;
    // Barycentric coordinates of d in the triangle (origin, origin + e1, origin + e2).
    const double b1 = glm::dot(glm::cross(d, m.e2), m.normal) / (normalLength * normalLength);
    const double b2 = glm::dot(glm::cross(m.e1, d), m.normal) / (normalLength * normalLength);
    const glm::dvec2 predicted = m.uv0 + b1 * (m.uv1 - m.uv0) + b2 * (m.uv2 - m.uv0);
    const glm::dvec2 difference = predicted - glm::dvec2(scene.uvs[v]);
    if (!shift) shift = glm::round(difference);
    const glm::dvec2 error = (difference - *shift) * texels;
    if (!(std::abs(error.x) <= 0.01 && std::abs(error.y) <= 0.01)) return std::nullopt;
  }
  if (!shift || std::abs(shift->x) > 1e9 || std::abs(shift->y) > 1e9) return std::nullopt;
  return glm::i64vec2(*shift);
}

// Candidate pairs: faces of one texture that share a vertex position.
std::set<std::pair<uint32_t, uint32_t>> candidatePairs(const TexturedScene& scene) {
  const auto faceCount = static_cast<uint32_t>(scene.faces.size());
  std::map<PositionBits, std::vector<uint32_t>> facesAt;
  for (uint32_t f = 0; f < faceCount; ++f) {
    const TexturedFace& face = scene.faces[f];
    for (uint32_t i = face.firstIndex; i < face.firstIndex + face.indexCount; ++i) {
      std::vector<uint32_t>& faces = facesAt[positionBits(scene.positions[scene.indices[i]])];
      if (faces.empty() || faces.back() != f) faces.push_back(f);
    }
  }
  // Every two faces at a position form a pair: faces that share their vertices many times over
  // would give pairs by the square of their number. Counted, and refused, before any is formed.
  uint64_t visits = 0;
  for (const auto& [position, faces] : facesAt) visits += faces.size() * (faces.size() - 1) / 2;
  if (visits > kMaxChartPairs)
    throw limitError(describedSource(scene),
                     "pairing the faces that share a vertex position (every two at each position)",
                     visits, kMaxChartPairs, " pairs");
  std::set<std::pair<uint32_t, uint32_t>> pairs;
  for (const auto& [position, faces] : facesAt)
    for (size_t i = 0; i < faces.size(); ++i)
      for (size_t j = i + 1; j < faces.size(); ++j)
        if (faces[i] != faces[j] && scene.faces[faces[i]].texture == scene.faces[faces[j]].texture)
          pairs.emplace(std::min(faces[i], faces[j]), std::max(faces[i], faces[j]));
  return pairs;
}

// Each pair checks the vertices of its second face (repetitionShift): refused above the limit.
void requireFewVertexChecks(const TexturedScene& scene,
                            const std::set<std::pair<uint32_t, uint32_t>>& pairs) {
  uint64_t checks = 0;
  for (const auto& pair : pairs) checks += scene.faces[pair.second].indexCount;
  if (checks > kMaxChartVertexChecks)
    throw limitError(describedSource(scene),
                     "checking whether the faces of " + std::to_string(pairs.size()) +
                         " pairs lie in one plane with one texture map",
                     checks, kMaxChartVertexChecks, " vertices");
}

// Charts joined as a forest: each chart points to the chart it joined, with the shift from its
// space into that one's, so a join copies no faces. A face's chart is its root (chart f starts
// as face f alone) and its offset the sum of the shifts on the way; lookups shorten the way.
// A chart's faces are a list, in the order they joined: a root's list starts at its own face.
class ChartForest {
 public:
  static constexpr uint32_t kEnd = UINT32_MAX;

  explicit ChartForest(uint32_t faceCount)
      : joined_(faceCount),
        shiftTo_(faceCount, glm::i64vec2(0)),
        nextFace_(faceCount, kEnd),
        lastFace_(faceCount) {
    std::iota(joined_.begin(), joined_.end(), 0u);
    std::iota(lastFace_.begin(), lastFace_.end(), 0u);
  }

  // The root of `face`'s chart and the face's offset in it.
  std::pair<uint32_t, glm::i64vec2> chartOf(uint32_t face) {
    glm::i64vec2 offset(0);
    uint32_t root = face;
    for (; joined_[root] != root; root = joined_[root]) offset += shiftTo_[root];
    glm::i64vec2 remaining = offset;
    for (uint32_t c = face; joined_[c] != c;) {
      const uint32_t up = joined_[c];
      const glm::i64vec2 step = shiftTo_[c];
      joined_[c] = root;
      shiftTo_[c] = remaining;
      remaining -= step;
      c = up;
    }
    return std::pair{root, offset};
  }

  // Root b joins root a, its space moved by `move` into a's.
  void join(uint32_t a, uint32_t b, glm::i64vec2 move) {
    joined_[b] = a;
    shiftTo_[b] = move;
    nextFace_[lastFace_[a]] = b;
    lastFace_[a] = lastFace_[b];
  }

  bool isRoot(uint32_t c) const { return joined_[c] == c; }
  uint32_t nextFace(uint32_t face) const { return nextFace_[face]; }

 private:
  std::vector<uint32_t> joined_;
  std::vector<glm::i64vec2> shiftTo_;
  std::vector<uint32_t> nextFace_, lastFace_;
};

// Chart b moved by `move` into chart a's space, joined with a, unless the union would be wider or
// taller than maxSide or waste more than `slack` of the two charts' area.
std::optional<Chart> mergedIfCompact(const Chart& a, const Chart& b, glm::i64vec2 move,
                                     const ChartOptions& options) {
  Chart merged;
  merged.texture = a.texture;
  merged.x0 = std::min(a.x0, b.x0 + move.x);
  merged.y0 = std::min(a.y0, b.y0 + move.y);
  merged.x1 = std::max(a.x1, b.x1 + move.x);
  merged.y1 = std::max(a.y1, b.y1 + move.y);
  if (merged.width() > options.maxSide || merged.height() > options.maxSide ||
      double(area(merged)) > (1.0 + options.slack) * double(area(a) + area(b)))
    return std::nullopt;
  return merged;
}

// Joins the charts of each pair whose faces repeat one texture map, where the union is compact.
void joinRepeatingPairs(const TexturedScene& scene, const ChartOptions& options,
                        const std::set<std::pair<uint32_t, uint32_t>>& pairs,
                        const std::vector<PlaneMapping>& mappings, std::vector<Chart>& charts,
                        ChartForest& forest) {
  for (const auto& [p, q] : pairs) {
    const auto [a, offsetP] = forest.chartOf(p);
    const auto [b, offsetQ] = forest.chartOf(q);
    if (a == b) continue;
    const auto shift = repetitionShift(scene, mappings[p], scene.faces[q]);
    if (!shift) continue;
    // q's coordinates + shift are p's; chart b's space -> chart a's space:
    const SourceTexture& texture = scene.textures[scene.faces[p].texture];
    const glm::i64vec2 move =
        *shift * glm::i64vec2(texture.width, texture.height) + offsetP - offsetQ;
    const std::optional<Chart> merged = mergedIfCompact(charts[a], charts[b], move, options);
    if (!merged) continue;
    charts[a].x0 = merged->x0, charts[a].y0 = merged->y0;
    charts[a].x1 = merged->x1, charts[a].y1 = merged->y1;
    forest.join(a, b, move);
  }
}

// The root charts, each with its faces in the order they joined and their offsets.
std::vector<Chart> rootCharts(std::vector<Chart>& charts, ChartForest& forest) {
  const auto faceCount = static_cast<uint32_t>(charts.size());
  std::vector<Chart> result;
  for (uint32_t c = 0; c < faceCount; ++c) {
    if (!forest.isRoot(c)) continue;
    Chart& chart = result.emplace_back(std::move(charts[c]));
    chart.faces.clear();
    chart.offsets.clear();
    for (uint32_t face = c; face != ChartForest::kEnd; face = forest.nextFace(face)) {
      chart.faces.push_back(face);
      chart.offsets.push_back(forest.chartOf(face).second);
    }
  }
  return result;
}

}  // namespace

Chart faceChart(const TexturedScene& scene, uint32_t face, uint32_t margin) {
  const TexelBounds bounds = faceTexelBounds(scene, scene.faces[face]);
  Chart chart{.texture = scene.faces[face].texture, .faces = {face}, .offsets = {{0, 0}}};
  chart.x0 = static_cast<int64_t>(std::floor(bounds.u0)) - margin;
  chart.y0 = static_cast<int64_t>(std::floor(bounds.v0)) - margin;
  chart.x1 = std::max(static_cast<int64_t>(std::ceil(bounds.u1)) + margin, chart.x0 + 1);
  chart.y1 = std::max(static_cast<int64_t>(std::ceil(bounds.v1)) + margin, chart.y0 + 1);
  return chart;
}

std::vector<Chart> buildCharts(const TexturedScene& scene, const ChartOptions& options) {
  const auto faceCount = static_cast<uint32_t>(scene.faces.size());
  std::vector<Chart> charts;
  charts.reserve(faceCount);
  for (uint32_t f = 0; f < faceCount; ++f) charts.push_back(faceChart(scene, f, options.margin));

  const std::set<std::pair<uint32_t, uint32_t>> pairs = candidatePairs(scene);
  requireFewVertexChecks(scene, pairs);
  std::vector<PlaneMapping> mappings;
  mappings.reserve(faceCount);
  for (const TexturedFace& face : scene.faces) mappings.push_back(planeMapping(scene, face));

  ChartForest forest(faceCount);
  joinRepeatingPairs(scene, options, pairs, mappings, charts, forest);
  return rootCharts(charts, forest);
}

}  // namespace vt
