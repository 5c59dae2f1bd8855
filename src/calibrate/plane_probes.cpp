#include "calibrate/plane_probes.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "calibrate/family_fit.h"
#include "calibrate/float_bits.h"

namespace vt::calibrate {
namespace {

constexpr double kDepthUnit = 0x1p-24;
constexpr double kCoordinateUnit = 0x1p-20;

// T's vertices in window pixels (multiples of 1/256, inside a 64 x 64 cell) and coordinates.
constexpr glm::dvec2 kCorners[3] = {{4 + 65 / 256.0, 6 + 129 / 256.0},
                                    {58 + 193 / 256.0, 20 + 33 / 256.0},
                                    {22 + 127 / 256.0, 59 + 67 / 256.0}};
constexpr glm::dvec2 kCoordinates[3] = {
    {0.125 + 3 * kCoordinateUnit, 0.75 - 5 * kCoordinateUnit},
    {0.8125 + 7 * kCoordinateUnit, 0.1875 + kCoordinateUnit},
    {0.40625 - 9 * kCoordinateUnit, 0.96875 + 11 * kCoordinateUnit}};

// Window depths of T's vertices: multiples of 2^-24, so that 2 z - 1 (the clip depth at w = 1)
// and back are exact.
using Depths = std::array<double, 3>;
constexpr Depths kMiddleDepths = {0.3125 + 4097 * kDepthUnit, 0.6875 - 3 * kDepthUnit,
                                  0.5 + 77 * kDepthUnit};
constexpr Depths kNearOneDepths = {1 - 16777 * kDepthUnit, 1 - 16001 * kDepthUnit,
                                   1 - 17099 * kDepthUnit};
constexpr Depths kNearTinyDepths = {(16384 + 11) * kDepthUnit, (16384 + 3001) * kDepthUnit,
                                    (16384 + 1499) * kDepthUnit};

struct TriangleVariant {
  Depths depths = kMiddleDepths;
  std::array<float, 3> w = {1, 1, 1};
  int rotation = 0;  // the vertex drawn first: 0, 1 or 2 (T's order kept)
};

// Appends a triangle with its own three vertices, at window positions `window` (pixels), depth
// `depth` and w, in `viewport` (sides powers of two, so that the window positions convert to
// clip space and back exactly).
void addTriangle(ClipSpaceMesh& mesh, Viewport viewport, const std::array<glm::dvec2, 3>& window,
                 const Depths& depth, const std::array<float, 3>& w,
                 const std::array<glm::dvec2, 3>& uv) {
  const double halfWidth = viewport.width / 2.0, halfHeight = viewport.height / 2.0;
  for (int v = 0; v < 3; ++v) {
    const auto x = static_cast<float>(window[v].x / halfWidth - 1);
    const auto y = static_cast<float>(window[v].y / halfHeight - 1);
    const auto z = static_cast<float>(2 * depth[v] - 1);
    mesh.vertices.push_back({{x * w[v], y * w[v], z * w[v], w[v]},
                             {static_cast<float>(uv[v].x), static_cast<float>(uv[v].y)}});
    mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
  }
}

void addT(ClipSpaceMesh& mesh, Viewport viewport, glm::ivec2 offset, const TriangleVariant& t) {
  std::array<glm::dvec2, 3> window, uv;
  Depths depth;
  std::array<float, 3> w;
  for (int v = 0; v < 3; ++v) {
    const int from = (v + t.rotation) % 3;
    window[v] = kCorners[from] + glm::dvec2(offset);
    uv[v] = kCoordinates[from];
    depth[v] = t.depths[from];
    w[v] = t.w[from];
  }
  addTriangle(mesh, viewport, window, depth, w, uv);
}

PlaneProbe triangleProbe(std::string name, Viewport viewport, std::vector<glm::ivec2> copies,
                         const TriangleVariant& variant = {}) {
  PlaneProbe probe{std::move(name), {}, viewport, DepthFormat::kDepth32F, std::move(copies)};
  for (const glm::ivec2 offset : probe.copies) addT(probe.mesh, viewport, offset, variant);
  return probe;
}

// Window depths for the squares: per group of four, the float nearest a tie (k + 1/2) / (2^24 -
// 1) of the Z24 conversion, its two float neighbours, and a float drawn uniformly from [0.25, 1)
// by its bits; all in [0.25, 1), where 2 z - 1 is exact.
std::vector<double> squareDepths(size_t count) {
  std::mt19937 random(24);
  std::uniform_int_distribution<uint32_t> tie(uint32_t{1} << 22, (uint32_t{1} << 24) - 16);
  std::uniform_int_distribution<uint32_t> bits(std::bit_cast<uint32_t>(0.25f),
                                               std::bit_cast<uint32_t>(1.0f) - 1);
  std::vector<double> depths;
  while (depths.size() < count) {
    const float nearest = static_cast<float>((tie(random) + 0.5) / 16777215.0);
    depths.push_back(nearest);
    depths.push_back(std::nextafter(nearest, 2.0f));
    depths.push_back(std::nextafter(nearest, 0.0f));
    depths.push_back(std::bit_cast<float>(bits(random)));
  }
  depths.resize(count);
  return depths;
}

// 64 x 64 squares of 4 x 4 pixels, each two triangles at one depth, their corners a quarter pixel
// right of the pixel grid so that no pixel centre lies on an edge.
PlaneProbe constantDepthSquares() {
  constexpr int kSide = 64, kSquare = 4;
  PlaneProbe probe{
      "constant-depth squares", {}, {kSide * kSquare, kSide * kSquare}, DepthFormat::kDepth24, {}};
  const std::vector<double> depths = squareDepths(kSide * kSide);
  const std::array<glm::dvec2, 3> uv = {glm::dvec2(0.5), glm::dvec2(0.5), glm::dvec2(0.5)};
  const std::array<float, 3> w = {1, 1, 1};
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const double z = depths[static_cast<size_t>(j * kSide + i)];
      const glm::dvec2 lo(i * kSquare + 0.25, j * kSquare), hi = lo + glm::dvec2(kSquare);
      addTriangle(probe.mesh, probe.viewport, {lo, glm::dvec2(hi.x, lo.y), hi}, {z, z, z}, w, uv);
      addTriangle(probe.mesh, probe.viewport, {lo, hi, glm::dvec2(lo.x, hi.y)}, {z, z, z}, w, uv);
    }
  return probe;
}

// The index of pixel (x, y) of `v`, or SIZE_MAX outside it.
size_t pixelAt(Viewport v, int x, int y) {
  return x >= 0 && y >= 0 && x < v.width && y < v.height ? static_cast<size_t>(y) * v.width + x
                                                         : SIZE_MAX;
}

bool sameValues(const RasterReadback& a, size_t i, const RasterReadback& b, size_t j) {
  return sameBits(a.uv[i].x, b.uv[j].x) && sameBits(a.uv[i].y, b.uv[j].y) &&
         sameBits(a.derivatives[i].x, b.derivatives[j].x) &&
         sameBits(a.derivatives[i].y, b.derivatives[j].y) &&
         sameBits(a.derivatives[i].z, b.derivatives[j].z) &&
         sameBits(a.derivatives[i].w, b.derivatives[j].w) && sameBits(a.depth[i], b.depth[j]);
}

// `count` random triangles with their vertices on the 1/256 grid of a 256 x 256 viewport, within
// `reach` pixels of a centre (the whole viewport for reach 0), window depths multiples of 2^-24
// in [0.25, 0.75), w of 0.5, 1, 2 or 4 and random coordinates.
NoperspectiveProbe randomGridTriangles(std::string name, unsigned seed, int count, int reach) {
  NoperspectiveProbe probe{std::move(name), {}, {}, {256, 256}};
  std::mt19937 random(seed);
  const auto grid = [&](int lo, int hi) {  // a multiple of 1/256 in [lo, hi)
    return std::uniform_int_distribution<int>(lo * 256, hi * 256 - 1)(random) / 256.0;
  };
  std::uniform_int_distribution<uint32_t> depth(uint32_t{1} << 22, 3 * (uint32_t{1} << 22) - 1);
  std::uniform_real_distribution<float> coordinate(0.0f, 1.0f);
  constexpr float kW[4] = {0.5f, 1, 2, 4};
  for (int k = 0; k < count; ++k) {
    std::array<glm::dvec2, 3> window, uv;
    Depths z;
    std::array<float, 3> w;
    const glm::dvec2 centre(grid(reach, 256 - reach), grid(reach, 256 - reach));
    for (int v = 0; v < 3; ++v) {
      window[v] = reach == 0 ? glm::dvec2(grid(0, 256), grid(0, 256))
                             : centre + glm::dvec2(grid(-reach, reach), grid(-reach, reach));
      z[v] = depth(random) * kDepthUnit;
      w[v] = kW[random() % 4];
      uv[v] = glm::dvec2(coordinate(random), coordinate(random));
    }
    addTriangle(probe.drawn, probe.viewport, window, z, w, uv);
    addTriangle(probe.divided, probe.viewport, window, z, {1, 1, 1}, uv);
  }
  return probe;
}

}  // namespace

std::vector<NoperspectiveProbe> noperspectiveProbes() {
  return {randomGridTriangles("small triangles", 31, 400, 16),
          randomGridTriangles("large triangles", 32, 60, 0)};
}

std::vector<PlaneProbe> planeProbes() {
  const Viewport cell{128, 128};
  std::vector<PlaneProbe> probes;
  probes.push_back(triangleProbe("base", cell, {{0, 0}}));
  for (int k = 0; k <= 5; ++k)
    probes.push_back(triangleProbe("shift " + std::to_string(1 << k), cell, {{1 << k, 1 << k}}));
  probes.push_back(
      triangleProbe("x copies", {1024, 64}, {{0, 0}, {64, 0}, {128, 0}, {256, 0}, {512, 0}}));
  probes.push_back(
      triangleProbe("y copies", {64, 1024}, {{0, 0}, {0, 64}, {0, 128}, {0, 256}, {0, 512}}));
  probes.push_back(triangleProbe("depths near 1", cell, {{0, 0}}, {kNearOneDepths}));
  probes.push_back(triangleProbe("depths near 2^-10", cell, {{0, 0}}, {kNearTinyDepths}));
  for (const int rotation : {1, 2})
    probes.push_back(triangleProbe("rotation " + std::to_string(rotation), cell, {{0, 0}},
                                   {kMiddleDepths, {1, 1, 1}, rotation}));
  probes.push_back(triangleProbe("w 0.5, 2, 3", cell, {{0, 0}}, {kMiddleDepths, {0.5f, 2, 3}}));
  probes.push_back(constantDepthSquares());
  return probes;
}

ShiftEvidence shiftEvidence(const std::vector<PlaneProbe>& probes,
                            const std::vector<RasterReadback>& drawn) {
  ShiftEvidence evidence;
  for (size_t d = 0; d < probes.size(); ++d) {
    const PlaneProbe& probe = probes[d];
    // The unshifted copy: this draw's own where it has one (triangle 0), else the base's.
    const bool own = !probe.copies.empty() && probe.copies[0] == glm::ivec2(0);
    const PlaneProbe& base = own ? probe : probes[0];
    const RasterReadback& reference = own ? drawn[d] : drawn[0];
    for (size_t c = own ? 1 : 0; c < probe.copies.size(); ++c) {
      const glm::ivec2 shift = probe.copies[c];
      uint64_t differing = 0;
      // Both ways: every pixel of the copy against the base pixel behind it, and every base
      // pixel whose shifted pixel is not the copy's.
      for (int y = 0; y < probe.viewport.height; ++y)
        for (int x = 0; x < probe.viewport.width; ++x) {
          const size_t p = pixelAt(probe.viewport, x, y);
          if (drawn[d].triangle[p] != static_cast<int32_t>(c)) continue;
          ++evidence.pixels;
          const size_t q = pixelAt(base.viewport, x - shift.x, y - shift.y);
          differing +=
              q == SIZE_MAX || reference.triangle[q] != 0 || !sameValues(drawn[d], p, reference, q);
        }
      for (int y = 0; y < base.viewport.height; ++y)
        for (int x = 0; x < base.viewport.width; ++x) {
          if (reference.triangle[pixelAt(base.viewport, x, y)] != 0) continue;
          const size_t p = pixelAt(probe.viewport, x + shift.x, y + shift.y);
          if (p == SIZE_MAX || drawn[d].triangle[p] != static_cast<int32_t>(c)) {
            ++evidence.pixels;
            ++differing;
          }
        }
      evidence.differing += differing;
      const int size = std::max(shift.x, shift.y);
      if (differing && (evidence.smallestShift == 0 || size < evidence.smallestShift))
        evidence.smallestShift = size;
    }
  }
  return evidence;
}

std::string shiftFinding(const ShiftEvidence& e) {
  const std::string pixels = " (" + differ(e.differing, e.pixels) +
                             " of the shifted copies' pixels against the unshifted triangle)";
  if (e.differing == 0)
    return "a triangle shifted by 1 to 512 pixels keeps its values bit for bit: the planes are "
           "evaluated from a point that moves with it" +
           pixels;
  return "the values of a triangle shifted by 1 to 512 pixels change from a shift of " +
         std::to_string(e.smallestShift) + ": the planes are evaluated from a fixed origin" +
         pixels;
}

}  // namespace vt::calibrate
