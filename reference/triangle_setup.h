#pragma once
// Triangle setup as a GL rasterizer does it, in the members of the arithmetic's families that
// concern it (render/arithmetic.h): clipping against the frustum (docs/design.md section 7, rule
// 5), the window transform (fused or not), coverage (snapped integer edge functions with a
// sub-pixel grid, rounding and tie rule, or float scanline spans over unsnapped vertices:
// reference/softpipe-arithmetic.md, 2.3), and the attribute planes (from the first vertex of the
// oriented triangle, rule 3, or from the lowest vertex, softpipe-arithmetic.md 3.1).
//
// Window conventions (GL, framebuffer object):
//
//      y ^   pixel (px, py) has its centre at (px + 0.5, py + 0.5); row 0 is at the bottom
//        |   +-----+-----+
//      1 |   | 0,1 | 1,1 |     2x2 quads start at even (px, py): the quad of (3, 2) is
//        |   +-----+-----+     (2, 2) (3, 2) (2, 3) (3, 3)
//      0 |   | 0,0 | 1,0 |
//        |   +-----+-----+
//        +---------------> x
//
// Snapped coordinates are (X - 0.5) * 2^bits rounded as the coverage member says (8 bits, half to
// even in rule 2), so pixel centres lie on multiples of 2^bits. A centre exactly on an edge
// belongs to the triangle when the edge is of the kinds the tie rule names (left and bottom in
// rule 4), so a mesh that shares edges covers every pixel once.

#include <array>
#include <cmath>
#include <cstdint>
#include <glm/vec2.hpp>
#include <vector>

#include "render/arithmetic.h"
#include "scene/clip_space_mesh.h"

namespace vt::reference {

// a(px, py) = a0 + dadx * px + dady * py, at the centre of pixel (px, py) (rule 3).
struct Plane {
  float dadx = 0.0f, dady = 0.0f, a0 = 0.0f;
};

// A plane at integer pixel coordinates (rule 6), fused or not; or evaluated at its quad's origin
// (x0, y0), both even, and stepped to the other three pixels: (a0 + dadx * x0) + dady * y0, then
// + dadx for the right column, + dady for the upper row (softpipe-arithmetic.md, 3.2).
inline float evaluatePlane(const Plane& plane, int px, int py, PlaneEvaluation evaluation) {
  if (evaluation == PlaneEvaluation::kQuadStepped) {
    float value = (plane.a0 + plane.dadx * static_cast<float>(px & ~1)) +
                  plane.dady * static_cast<float>(py & ~1);
    if (px & 1) value = value + plane.dadx;
    if (py & 1) value = value + plane.dady;
    return value;
  }
  const float x = static_cast<float>(px), y = static_cast<float>(py);
  return evaluation == PlaneEvaluation::kFused
             ? std::fma(plane.dady, y, std::fma(plane.dadx, x, plane.a0))
             : plane.dady * y + (plane.dadx * x + plane.a0);
}

// Edge function of rule 4 on a grid of 2^bits per pixel: covered when
// c + 2^bits * (b * py - a * px) > 0 for all three edges.
struct Edge {
  int64_t a = 0, b = 0, c = 0;
  int bits = 8;
  int64_t at(int64_t px, int64_t py) const { return c + (b * py - a * px) * (int64_t{1} << bits); }
};

// A corner of a set-up triangle before snapping: window position, window z, 1/w and the
// perspective attributes s/w and t/w. The result sets (result_set.h) interpolate from these.
struct WindowCorner {
  float x = 0, y = 0, z = 0, oow = 0, sw = 0, tw = 0;
  // Pixels between the corner's window position and that of the same corner clipped in double
  // precision: 0 for a mesh vertex; for a vertex the clipper made, how far the float clipping
  // moved it (a huge polygon cut near the camera: pixels). Another conforming clipper may land as
  // far the other way, so the result sets let the corner move twice this, and the candidates'
  // boxes grow by SetupTriangle::candidateMargin (reference/result_set_builder.cpp,
  // visibility.cpp). clipDepthError: the same for its window z (depth units); the result sets'
  // depth widens by twice it, weighted by the corner's barycentric coordinate.
  float clipError = 0, clipDepthError = 0;
  // The size of the terms any float computation of the corner's window z sums, in depth units:
  // sum_i beta_i (|z_i| + |w_i|) / (2 |w|) for the corner = sum_i beta_i V_i of the mesh
  // triangle's clip-space vertices V_i (beta >= 0, sum 1); 0 for the corners of an unclipped
  // triangle, which lie inside the depth range where the terms are at most 1, the result sets'
  // least unit. A corner the clipper made from a vertex behind the camera (w < 0) sums terms far
  // larger than its value: clipping computes it as a difference of such terms, and a rasterizer
  // that clips nothing (homogeneous barycentrics, the exact polygon) evaluates sum_i l_i V_i with
  // l_i = beta_i / w, whose terms are these too. The quantity over |w| is affine in window
  // space (as 1/w is), so at a pixel it is the corners' values interpolated by its barycentric
  // coordinates; the result sets scale the depth error by it (result_set_builder.cpp). Capped at
  // 2^23 (every depth).
  float depthTerms = 0;
};

// softpipe's coverage of one half of a triangle (the rows below its middle vertex, or from it up):
// `rows` rows from `firstRow`; row firstRow + i spans the pixels left <= px < right with
// left = trunc(left.sx + i * left.dxdy) and right likewise, clamped to [0, width)
// (reference/softpipe-arithmetic.md, 2.3).
struct ScanlineHalf {
  struct Edge {
    float sx = 0.0f, dxdy = 0.0f;
  };
  int firstRow = 0, rows = 0;
  Edge left, right;
  // The span of row py, or an empty one (left >= right) outside the half.
  std::array<int, 2> span(int py, int width) const;
};

// One triangle as the rasterizer sees it: after clipping (a clipped triangle becomes a fan of
// several), oriented, with its planes.
struct SetupTriangle {
  uint32_t primitive = 0;  // index of the mesh triangle (draw order)
  uint32_t fanIndex = 0;   // position in the clipped fan (draw order within the primitive)
  std::array<Edge, 3> edges;
  Plane s, t;                                    // perspective attributes: s/w and t/w
  Plane oneOverW;                                // 1/w
  Plane z;                                       // window z, not perspective-divided
  int minX = 0, minY = 0, maxX = -1, maxY = -1;  // pixels whose centres may be covered
  std::array<WindowCorner, 3> corners;           // in the oriented order of the edges
  // Pixels by which the candidates' boxes grow: twice the corners' largest clipError, where that
  // passes the quarter pixel the boxes keep (visibility.cpp).
  int candidateMargin = 0;
  // Per edge (opposite corner i): 0 on the mesh triangle's boundary; +1 or -1 inside a clipped
  // fan, shared with the triangle of fanIndex + 1 or - 1 (the shared-edge rule gives its pixels
  // to one of the two).
  std::array<int8_t, 3> fanNeighbour{};
  // Scanline coverage instead of `edges`; a row of both halves takes the top half's span unless it
  // is empty (the order softpipe writes them).
  bool scanline = false;
  int width = 0;                       // the viewport's, the spans' clip
  std::array<ScanlineHalf, 2> halves;  // bottom, top

  bool covers(int px, int py) const {
    if (scanline) {
      for (const ScanlineHalf* half : {&halves[1], &halves[0]}) {
        const std::array<int, 2> span = half->span(py, width);
        if (span[0] < span[1]) return span[0] <= px && px < span[1];
      }
      return false;
    }
    return edges[0].at(px, py) > 0 && edges[1].at(px, py) > 0 && edges[2].at(px, py) > 0;
  }

  // The pixels of row py within [lo, hi] whose centres the triangle covers, first and last
  // (first > last when none): exactly those where covers() holds, solved per edge in integers
  // (each edge function is linear in px along a row) instead of tested pixel by pixel.
  std::array<int, 2> coveredSpan(int py, int lo, int hi) const {
    if (scanline) {
      for (const ScanlineHalf* half : {&halves[1], &halves[0]}) {
        const std::array<int, 2> span = half->span(py, width);
        if (span[0] < span[1]) return {std::max(span[0], lo), std::min(span[1] - 1, hi)};
      }
      return {1, 0};
    }
    // floor(n / d) for d > 0.
    const auto floorDiv = [](int64_t n, int64_t d) { return n / d - (n % d != 0 && n < 0); };
    int64_t first = lo, last = hi;
    for (const Edge& e : edges) {
      // at(px, py) = row - step * px, which must be > 0.
      const int64_t scale = int64_t{1} << e.bits;
      const int64_t row = e.c + e.b * py * scale, step = e.a * scale;
      if (step > 0)
        last = std::min(last, floorDiv(row - 1, step));
      else if (step < 0)
        first = std::max(first, floorDiv(-row, -step) + 1);
      else if (row <= 0)
        return {1, 0};
    }
    if (first > last) return {1, 0};
    return {static_cast<int>(first), static_cast<int>(last)};
  }
};

// The texture coordinates (s/w and t/w over 1/w) of a set-up triangle at pixel (px, py), and 1/w:
// multiplied by the reciprocal of the 1/w plane or divided by it (the perspective family).
struct PixelAttributes {
  glm::vec2 uv;
  float w;
};
inline PixelAttributes attributesAt(const SetupTriangle& t, int px, int py,
                                    const Arithmetic& arithmetic) {
  const PlaneEvaluation evaluation = arithmetic.planeEvaluation;
  const float q = evaluatePlane(t.oneOverW, px, py, evaluation);
  const float recip = arithmetic.reciprocal.of(q);
  const float s = evaluatePlane(t.s, px, py, evaluation),
              tt = evaluatePlane(t.t, px, py, evaluation);
  if (arithmetic.perspective == Perspective::kDivided) return {glm::vec2(s / q, tt / q), recip};
  return {glm::vec2(s * recip, tt * recip), recip};
}

struct SetupStatistics {
  uint64_t triangles = 0;  // mesh triangles
  uint64_t nonFinite = 0;  // dropped: a NaN or infinite position or clip distance
  uint64_t culled = 0;     // entirely outside one frustum plane
  uint64_t clipped = 0;    // crossed a frustum plane
  uint64_t empty = 0;      // (fan) triangles of zero snapped area or no pixel centre inside
                           // the viewport: they draw nothing
};

// Sets up every triangle of `mesh` for `viewport` in the arithmetic's members. With a fused
// viewport the window transform of the mesh's vertices (x, y and z) uses fma; vertices made by
// clipping, and the plane setup itself (rule 3), never fuse.
std::vector<SetupTriangle> setupTriangles(const ClipSpaceMesh& mesh, Viewport viewport,
                                          const Arithmetic& arithmetic,
                                          SetupStatistics* statistics = nullptr);

}  // namespace vt::reference
