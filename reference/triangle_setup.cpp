#include "reference/triangle_setup.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

#include "common/parallel_for.h"

namespace vt::reference {
namespace {

// A clip-space vertex with its perspective attributes, as the clipper carries it. Vertices the
// clipper makes get their window coordinates from llvmpipe's C clipper, without fma. `exact`: the
// position clipped in double precision alongside, the same planes in the same order. `depthSum`:
// sum_i beta_i (|z_i| + |w_i|) over the mesh triangle's vertices i, beta the clip-space
// barycentric weights of the point (|z| + |w| at a vertex), linear in beta like the position, so
// clipped alongside it in double.
struct ClipPoint {
  glm::vec4 position;
  glm::vec2 uv;
  bool generated = false;
  glm::dvec4 exact{0.0};
  double depthSum = 0;
};

// Frustum planes in outcode bit order (rule 5): x > w, x + w < 0, y > w, y + w < 0, z + w < 0,
// z > w are outside. Distances are dot products with these, inside when >= 0.
constexpr std::array<glm::vec4, 6> kPlanes = {
    {{-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1}}};

unsigned outcode(const glm::vec4& p) {
  return (p.x > p.w ? 1u : 0u) | (p.x + p.w < 0 ? 2u : 0u) | (p.y > p.w ? 4u : 0u) |
         (p.y + p.w < 0 ? 8u : 0u) | (p.z + p.w < 0 ? 16u : 0u) | (p.z > p.w ? 32u : 0u);
}

// Float dot product summed left to right, never fused.
float distance(const glm::vec4& p, const glm::vec4& plane) {
  float sum = p.x * plane.x;
  sum = sum + p.y * plane.y;
  sum = sum + p.z * plane.z;
  sum = sum + p.w * plane.w;
  return sum;
}

// The point where the edge between an inside vertex (distance >= 0) and an outside one crosses
// the plane, interpolated from the endpoint nearer the plane (the inside one on a tie), in plain
// float: base + t * (other - base) with t = d_base / (d_base - d_other) <= 1/2.
ClipPoint intersect(const ClipPoint& inside, float dIn, const ClipPoint& outside, float dOut,
                    unsigned planeIndex) {
  const bool fromOutside = -dOut < dIn;
  const ClipPoint& base = fromOutside ? outside : inside;
  const ClipPoint& other = fromOutside ? inside : outside;
  const float dBase = fromOutside ? dOut : dIn, dOther = fromOutside ? dIn : dOut;
  const float t = dBase / (dBase - dOther);
  ClipPoint result;
  for (int k = 0; k < 4; ++k)
    result.position[k] = base.position[k] + t * (other.position[k] - base.position[k]);
  const glm::dvec4 plane(kPlanes[planeIndex]);
  const double eBase = glm::dot(base.exact, plane), eOther = glm::dot(other.exact, plane);
  const double te = eBase / (eBase - eOther);
  result.exact = base.exact + te * (other.exact - base.exact);
  result.depthSum = base.depthSum + te * (other.depthSum - base.depthSum);
  for (int k = 0; k < 2; ++k) result.uv[k] = base.uv[k] + t * (other.uv[k] - base.uv[k]);
  result.generated = true;
  return result;
}

// Sutherland-Hodgman against the planes set in `mask`, in bit order. Returns false when a
// distance is not finite (the triangle is dropped).
bool clipPolygon(std::vector<ClipPoint>& polygon, unsigned mask) {
  std::vector<ClipPoint> output;
  for (unsigned plane = 0; plane < 6 && polygon.size() >= 3; ++plane) {
    if (!(mask & (1u << plane))) continue;
    output.clear();
    ClipPoint previous = polygon.front();
    float dPrevious = distance(previous.position, kPlanes[plane]);
    if (!std::isfinite(dPrevious)) return false;
    for (size_t i = 1; i <= polygon.size(); ++i) {
      const ClipPoint& current = polygon[i % polygon.size()];
      const float d = distance(current.position, kPlanes[plane]);
      if (!std::isfinite(d)) return false;
      // Inside is a distance >= 0; a new vertex where the edge changes sides.
      const bool previousInside = dPrevious >= 0.0f, currentInside = d >= 0.0f;
      if (previousInside) output.push_back(previous);
      if (previousInside != currentInside)
        output.push_back(previousInside ? intersect(previous, dPrevious, current, d, plane)
                                        : intersect(current, d, previous, dPrevious, plane));
      previous = current;
      dPrevious = d;
    }
    polygon.swap(output);
  }
  return polygon.size() >= 3;
}

struct WindowVertex {
  float x, y, z, oow;  // window coordinates and 1/w
  int64_t xf, yf;      // snapped: round((X - 0.5) * 2^bits) as the coverage member says
  glm::vec2 uv;
  float clipError = 0, clipDepthError = 0, depthTerms = 0;  // WindowCorner's
};

// (X - 0.5) * 2^bits in float (exact for a power of two unless it overflows), rounded.
int64_t snap(float x, const Coverage& coverage) {
  const float scaled = (x - 0.5f) * std::ldexp(1.0f, coverage.subpixelBits);
  switch (coverage.rounding) {
    case SnapRounding::kHalfUp:
      return static_cast<int64_t>(std::floor(static_cast<double>(scaled) + 0.5));
    case SnapRounding::kFloor:
      return static_cast<int64_t>(std::floor(scaled));
    case SnapRounding::kCeil:
      return static_cast<int64_t>(std::ceil(scaled));
    case SnapRounding::kHalfEven:
      break;
  }
  return static_cast<int64_t>(std::nearbyint(scaled));
}

// Corner depth terms at or beyond this make every depth possible (2^23 units of 2^-23: the
// whole range per unit of error).
constexpr double kDepthTermsCap = 0x1p23;

WindowVertex toWindow(const ClipPoint& p, Viewport viewport, const Arithmetic& arithmetic) {
  WindowVertex v;
  v.oow = 1.0f / p.position.w;
  const float halfWidth = static_cast<float>(viewport.width) * 0.5f;
  const float halfHeight = static_cast<float>(viewport.height) * 0.5f;
  // llvmpipe's vertex pipeline applies the viewport with fused multiply-adds on an FMA CPU (the
  // measured rule 1 with rule 10); vertices its C clipper makes use a multiply and an add.
  const bool fma = arithmetic.fusedViewport && !p.generated;
  const float xNdc = p.position.x * v.oow, yNdc = p.position.y * v.oow;
  v.x = fma ? std::fma(xNdc, halfWidth, halfWidth) : xNdc * halfWidth + halfWidth;
  v.y = fma ? std::fma(yNdc, halfHeight, halfHeight) : yNdc * halfHeight + halfHeight;
  const float zNdc = p.position.z * v.oow;
  v.z = fma ? std::fma(zNdc, 0.5f, 0.5f) : zNdc * 0.5f + 0.5f;
  v.xf = snap(v.x, arithmetic.coverage);
  v.yf = snap(v.y, arithmetic.coverage);
  v.uv = p.uv;
  if (p.depthSum > 0) {
    // WindowCorner::depthTerms, for the corners of a clipped polygon (the clipper's and the mesh
    // vertices it keeps): depthSum over 2 |w| (window z is half of z / w), capped where it says
    // "anything" in depth units; NaN (an exact w of 0) too. An unclipped triangle's vertices lie
    // inside the depth range by the clip test, their terms at most 1 up to its float rounding,
    // which the result sets' least unit covers: left 0.
    const double terms = p.depthSum / (2.0 * std::fabs(p.exact.w));
    v.depthTerms = static_cast<float>(terms < kDepthTermsCap ? terms : kDepthTermsCap);
  }
  if (p.generated) {
    const double xe = (p.exact.x / p.exact.w + 1.0) * halfWidth;
    const double ye = (p.exact.y / p.exact.w + 1.0) * halfHeight;
    const double error = std::max(std::fabs(v.x - xe), std::fabs(v.y - ye));
    // NaN (an exact w of 0) or beyond float: as far as the viewport reaches.
    const double reach = 4.0 * (halfWidth + halfHeight);
    v.clipError = static_cast<float>(std::isfinite(error) ? std::min(error, reach) : reach);
    const double depthError = std::fabs(v.z - (p.exact.z / p.exact.w * 0.5 + 0.5));
    v.clipDepthError =
        static_cast<float>(std::isfinite(depthError) ? std::min(depthError, 1.0) : 1.0);
  }
  return v;
}

// Rule 3: the plane through a0, a1, a2 at the three vertices, in plain float.
Plane planeOf(float a0, float a1, float a2, float dx01, float dy01, float dx20, float dy20,
              float x0c, float y0c) {
  Plane plane;
  const float da01 = a0 - a1, da20 = a2 - a0;
  plane.dadx = da01 * dy20 - da20 * dy01;
  plane.dady = da20 * dx01 - da01 * dx20;
  plane.a0 = a0 - (plane.dadx * x0c + plane.dady * y0c);
  return plane;
}

// Rule 4: the edge from i to j with the tie rule. Of the oriented triangle's edges, a < 0 runs
// along its left side, a > 0 along its right, and a = 0 is its bottom (b > 0) or top (b < 0); the
// +1 gives a centre on the edge to the triangle.
Edge edgeOf(const WindowVertex& i, const WindowVertex& j, const Coverage& coverage) {
  Edge edge;
  edge.a = i.yf - j.yf;
  edge.b = i.xf - j.xf;
  edge.c = edge.a * i.xf - edge.b * i.yf;
  edge.bits = coverage.subpixelBits;
  const bool owned =
      edge.a != 0 ? (edge.a < 0) == coverage.leftEdgesIn : (edge.b >= 0) == coverage.bottomEdgesIn;
  if (owned) edge.c += 1;
  return edge;
}

// The plane setup from the first vertex of the oriented triangle (rule 3).
void firstVertexPlanes(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                       SetupTriangle& out) {
  const float dx01 = v0.x - v1.x, dy01 = v0.y - v1.y;
  const float dx20 = v2.x - v0.x, dy20 = v2.y - v0.y;
  const float ooa = 1.0f / (dx01 * dy20 - dy01 * dx20);
  const float x0c = v0.x - 0.5f, y0c = v0.y - 0.5f;
  const float sdx01 = dx01 * ooa, sdy01 = dy01 * ooa, sdx20 = dx20 * ooa, sdy20 = dy20 * ooa;
  const auto plane = [&](float a0, float a1, float a2) {
    return planeOf(a0, a1, a2, sdx01, sdy01, sdx20, sdy20, x0c, y0c);
  };
  out.oneOverW = plane(v0.oow, v1.oow, v2.oow);
  out.s = plane(v0.uv.x * v0.oow, v1.uv.x * v1.oow, v2.uv.x * v2.oow);
  out.t = plane(v0.uv.y * v0.oow, v1.uv.y * v1.oow, v2.uv.y * v2.oow);
  out.z = plane(v0.z, v1.z, v2.z);
}

WindowCorner cornerOf(const WindowVertex& v) {
  return WindowCorner{
      v.x,         v.y, v.z, v.oow, v.uv.x * v.oow, v.uv.y * v.oow, v.clipError, v.clipDepthError,
      v.depthTerms};
}

// The vertex at its snapped position (PlanePositions::kSnapped): X = 1/2 + xf 2^-bits, rounded to
// float (exact while |xf| < 2^24, positions within 2^(24 - bits) pixels).
WindowVertex onGrid(WindowVertex v, const Coverage& coverage) {
  v.x = static_cast<float>(0.5 + std::ldexp(static_cast<double>(v.xf), -coverage.subpixelBits));
  v.y = static_cast<float>(0.5 + std::ldexp(static_cast<double>(v.yf), -coverage.subpixelBits));
  return v;
}

// The planes as `setup` says, from the triangle in draw order (v0, v1, v2) or oriented.
void setupPlanes(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                 PlaneSetup setup, SetupTriangle& out);

// Coverage by snapped edge functions, and the planes; returns false when the snapped area is zero
// or no pixel centre of the viewport lies in the snapped bounds.
bool setupEdges(WindowVertex v0, WindowVertex v1, WindowVertex v2, Viewport viewport,
                const Arithmetic& arithmetic, bool clipped, SetupTriangle& out) {
  int64_t area = (v0.xf - v1.xf) * (v2.yf - v0.yf) - (v2.xf - v0.xf) * (v0.yf - v1.yf);
  if (area == 0) return false;
  if (area < 0) {
    std::swap(v0, v1);
    std::swap(out.fanNeighbour[0], out.fanNeighbour[1]);  // edge i is opposite corner i
  }
  // A clipped triangle's planes stay those through the float positions: its corners made by
  // clipping are no vertex a rasterizer that does not clip ever snaps (PlanePositions).
  if (arithmetic.planePositions == PlanePositions::kSnapped && !clipped)
    setupPlanes(onGrid(v0, arithmetic.coverage), onGrid(v1, arithmetic.coverage),
                onGrid(v2, arithmetic.coverage), arithmetic.planeSetup, out);
  else
    setupPlanes(v0, v1, v2, arithmetic.planeSetup, out);
  const Coverage& coverage = arithmetic.coverage;
  out.edges = {edgeOf(v0, v1, coverage), edgeOf(v1, v2, coverage), edgeOf(v2, v0, coverage)};
  out.corners = {cornerOf(v0), cornerOf(v1), cornerOf(v2)};

  // Pixels whose centres (multiples of 2^bits in snapped units) lie within the snapped bounds.
  const int64_t unit = int64_t{1} << coverage.subpixelBits;
  const auto ceilDiv = [unit](int64_t a) {
    return a >= 0 ? (a + unit - 1) / unit : -((-a) / unit);
  };
  const auto floorDiv = [unit](int64_t a) { return a >= 0 ? a / unit : -((-a + unit - 1) / unit); };
  const int64_t minXf = std::min({v0.xf, v1.xf, v2.xf}), maxXf = std::max({v0.xf, v1.xf, v2.xf});
  const int64_t minYf = std::min({v0.yf, v1.yf, v2.yf}), maxYf = std::max({v0.yf, v1.yf, v2.yf});
  out.minX = static_cast<int>(std::max<int64_t>(ceilDiv(minXf), 0));
  out.maxX = static_cast<int>(std::min<int64_t>(floorDiv(maxXf), viewport.width - 1));
  out.minY = static_cast<int>(std::max<int64_t>(ceilDiv(minYf), 0));
  out.maxY = static_cast<int>(std::min<int64_t>(floorDiv(maxYf), viewport.height - 1));
  return out.minX <= out.maxX && out.minY <= out.maxY;
}

// float to int as x86-64's cvttss2si converts it (the C casts of softpipe's setup): toward zero,
// and INT_MIN for NaN and values out of range.
int truncateToInt(float value) {
  if (!(value >= -2147483648.0f && value < 2147483648.0f)) return INT32_MIN;
  return static_cast<int>(value);
}

// One edge of softpipe's setup (sp_setup.c): from start to end, its x at the first row centre
// at or above the start, and its rows from there.
struct SpanEdge {
  float dx = 0, dy = 0, dxdy = 0, sx = 0, sy = 0;
};

SpanEdge spanEdge(const WindowVertex& from, const WindowVertex& to, float startX, float startY) {
  SpanEdge e;
  e.dx = to.x - from.x;
  e.dy = to.y - from.y;
  e.sy = std::ceil(startY);
  e.dxdy = e.dy != 0.0f ? e.dx / e.dy : 0.0f;
  e.sx = startX + (e.sy - startY) * e.dxdy;
  return e;
}

// The plane through values at vmin, vmid and vmax over the sorted edges (softpipe's
// tri_linear_coeff), with a0 its value at the centre of pixel (0, 0).
Plane lowestVertexPlane(float aMin, float aMid, float aMax, const SpanEdge& ebot,
                        const SpanEdge& emaj, float ooa, const WindowVertex& vmin) {
  const float botda = aMid - aMin, majda = aMax - aMin;
  const float a = ebot.dy * majda - botda * emaj.dy;
  const float b = emaj.dx * botda - majda * ebot.dx;
  Plane plane;
  plane.dadx = a * ooa;
  plane.dady = b * ooa;
  plane.a0 = aMin - (plane.dadx * (vmin.x - 0.5f) + plane.dady * (vmin.y - 0.5f));
  return plane;
}

// A triangle's vertices sorted by window y, ties by <= (softpipe's setup_sort_vertices), and its
// three edges from the pixel centres at or above their start (softpipe-arithmetic.md, 2.2).
struct SortedTriangle {
  const WindowVertex *vmin, *vmid, *vmax;
  SpanEdge emaj, ebot, etop;
  float ooa;  // 1 / area; not finite for a degenerate triangle
};

SortedTriangle sortedTriangle(const WindowVertex& v0, const WindowVertex& v1,
                              const WindowVertex& v2) {
  SortedTriangle s;
  if (v0.y <= v1.y) {
    if (v1.y <= v2.y) {
      s.vmin = &v0, s.vmid = &v1, s.vmax = &v2;
    } else if (v2.y <= v0.y) {
      s.vmin = &v2, s.vmid = &v0, s.vmax = &v1;
    } else {
      s.vmin = &v0, s.vmid = &v2, s.vmax = &v1;
    }
  } else {
    if (v0.y <= v2.y) {
      s.vmin = &v1, s.vmid = &v0, s.vmax = &v2;
    } else if (v2.y <= v1.y) {
      s.vmin = &v2, s.vmid = &v1, s.vmax = &v0;
    } else {
      s.vmin = &v1, s.vmid = &v2, s.vmax = &v0;
    }
  }
  // Pixel centres: + 0.5 on x, - 0.5 on y (sp_setup.c's pixel_offset).
  const float xMin = s.vmin->x + 0.5f, xMid = s.vmid->x + 0.5f;
  const float yMin = s.vmin->y - 0.5f, yMid = s.vmid->y - 0.5f;
  s.emaj = spanEdge(*s.vmin, *s.vmax, xMin, yMin);
  s.ebot = spanEdge(*s.vmin, *s.vmid, xMin, yMin);
  s.etop = spanEdge(*s.vmid, *s.vmax, xMid, yMid);
  const float area = s.emaj.dx * s.ebot.dy - s.ebot.dx * s.emaj.dy;
  s.ooa = 1.0f / area;
  return s;
}

// The planes from the lowest vertex over the sorted edges (softpipe-arithmetic.md, 3.1). They
// read emaj's dx and dy only, which advancing it to the top half leaves as they were.
void lowestVertexPlanes(const SortedTriangle& s, SetupTriangle& out) {
  const WindowVertex &vmin = *s.vmin, &vmid = *s.vmid, &vmax = *s.vmax;
  const auto plane = [&](float aMin, float aMid, float aMax) {
    return lowestVertexPlane(aMin, aMid, aMax, s.ebot, s.emaj, s.ooa, vmin);
  };
  out.z = plane(vmin.z, vmid.z, vmax.z);
  out.oneOverW = plane(vmin.oow, vmid.oow, vmax.oow);
  out.s = plane(vmin.uv.x * vmin.oow, vmid.uv.x * vmid.oow, vmax.uv.x * vmax.oow);
  out.t = plane(vmin.uv.y * vmin.oow, vmid.uv.y * vmid.oow, vmax.uv.y * vmax.oow);
}

void setupPlanes(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                 PlaneSetup setup, SetupTriangle& out) {
  if (setup == PlaneSetup::kLowestVertex)
    lowestVertexPlanes(sortedTriangle(v0, v1, v2), out);
  else
    firstVertexPlanes(v0, v1, v2, out);
}

// Coverage by float scanline spans over the unsnapped vertices (softpipe-arithmetic.md, 2.2 to
// 2.3), in draw order v0, v1, v2, and the planes; returns false when 1 / area is not finite or no
// pixel centre of the viewport is covered.
bool setupSpans(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                Viewport viewport, const Arithmetic& arithmetic, SetupTriangle& out) {
  SortedTriangle sorted = sortedTriangle(v0, v1, v2);
  if (!std::isfinite(sorted.ooa)) return false;
  SpanEdge& emaj = sorted.emaj;
  const SpanEdge &ebot = sorted.ebot, &etop = sorted.etop;
  const float yMid = sorted.vmid->y - 0.5f, yMax = sorted.vmax->y - 0.5f;
  const int bottomRows = truncateToInt(std::ceil(yMid - ebot.sy));
  const int topRows = truncateToInt(std::ceil(yMax - etop.sy));

  // The halves, as subtriangle() walks them: emaj is the left edge when the area is negative.
  // Both edges of the bottom half then advance by its rows, so emaj enters the top half from
  // there rather than recomputed at vmid.
  const auto half = [](const SpanEdge& left, const SpanEdge& right, int rows) {
    ScanlineHalf h;
    h.firstRow = truncateToInt(left.sy);
    h.rows = rows;
    h.left = {left.sx, left.dxdy};
    h.right = {right.sx, right.dxdy};
    return h;
  };
  const bool majorLeft = sorted.ooa < 0.0f;
  out.halves[0] = majorLeft ? half(emaj, ebot, bottomRows) : half(ebot, emaj, bottomRows);
  emaj.sx = emaj.sx + static_cast<float>(bottomRows) * emaj.dxdy;
  emaj.sy = emaj.sy + static_cast<float>(bottomRows);
  out.halves[1] = majorLeft ? half(emaj, etop, topRows) : half(etop, emaj, topRows);
  out.scanline = true;
  out.width = viewport.width;

  if (arithmetic.planeSetup == PlaneSetup::kLowestVertex)
    lowestVertexPlanes(sorted, out);  // the sort and edges made above
  else
    firstVertexPlanes(v0, v1, v2, out);
  out.corners = {cornerOf(v0), cornerOf(v1), cornerOf(v2)};

  // The pixels the spans cover inside the viewport bound the candidates exactly.
  out.minX = viewport.width, out.maxX = -1, out.minY = viewport.height, out.maxY = -1;
  for (const ScanlineHalf& h : out.halves) {
    const int first = std::max(h.firstRow, 0);
    const int64_t end =
        std::min<int64_t>(static_cast<int64_t>(h.firstRow) + h.rows, viewport.height);
    for (int py = first; py < end; ++py) {
      const std::array<int, 2> span = h.span(py, viewport.width);
      if (span[0] >= span[1]) continue;
      out.minX = std::min(out.minX, span[0]);
      out.maxX = std::max(out.maxX, span[1] - 1);
      out.minY = std::min(out.minY, py);
      out.maxY = std::max(out.maxY, py);
    }
  }
  return out.minX <= out.maxX && out.minY <= out.maxY;
}

}  // namespace

std::array<int, 2> ScanlineHalf::span(int py, int width) const {
  const int64_t i = static_cast<int64_t>(py) - firstRow;
  if (i < 0 || i >= rows) return {0, 0};
  const float row = static_cast<float>(i);
  const int l = std::max(truncateToInt(left.sx + row * left.dxdy), 0);
  const int r = std::min(truncateToInt(right.sx + row * right.dxdy), width);
  return {l, r};
}

namespace {

// Sets up mesh triangle k: culls, clips, and appends its (fan) triangles to `out`.
void setupPrimitive(const ClipSpaceMesh& mesh, size_t k, Viewport viewport,
                    const Arithmetic& arithmetic, std::vector<SetupTriangle>& out,
                    SetupStatistics& stats) {
  ++stats.triangles;
  std::vector<ClipPoint> polygon;
  polygon.reserve(9);
  unsigned any = 0, all = 63;
  bool finite = true;
  for (int corner = 0; corner < 3; ++corner) {
    const ClipVertex& v = mesh.vertices.at(mesh.indices[3 * k + static_cast<size_t>(corner)]);
    for (int c = 0; c < 4; ++c) finite = finite && std::isfinite(v.position[c]);
    const unsigned code = outcode(v.position);
    any |= code;
    all &= code;
    polygon.push_back({v.position, v.uv, false, glm::dvec4(v.position)});
  }
  if (!finite) {
    ++stats.nonFinite;
    return;
  }
  if (all != 0) {
    ++stats.culled;
    return;
  }
  if (any != 0) {
    ++stats.clipped;
    for (ClipPoint& p : polygon)
      p.depthSum = std::fabs(p.exact.z) + std::fabs(p.exact.w);  // ClipPoint's, for the clipper
    if (!clipPolygon(polygon, any)) {
      if (polygon.size() >= 3) ++stats.nonFinite;
      return;
    }
  }
  // A clipped polygon becomes the fan (p[i-1], p[i], p[0]) of rule 5; an unclipped triangle
  // keeps its vertex order (v0, v1, v2).
  for (size_t i = 2; i < polygon.size(); ++i) {
    SetupTriangle triangle;
    triangle.primitive = static_cast<uint32_t>(k);
    triangle.fanIndex = static_cast<uint32_t>(i - 2);
    const bool fan = any != 0;
    // Corners (p[i-1], p[i], p[0]): the edge p[i-1] p[i] is the polygon's; p[i] p[0] is shared
    // with the next triangle but for the last, p[0] p[i-1] with the previous but for the first.
    if (fan)
      triangle.fanNeighbour = {static_cast<int8_t>(i + 1 == polygon.size() ? 0 : 1),
                               static_cast<int8_t>(i == 2 ? 0 : -1), 0};
    const WindowVertex a = toWindow(polygon[fan ? i - 1 : 0], viewport, arithmetic);
    const WindowVertex b = toWindow(polygon[fan ? i : 1], viewport, arithmetic);
    const WindowVertex c = toWindow(polygon[fan ? 0 : 2], viewport, arithmetic);
    if (arithmetic.coverage.rule == CoverageRule::kScanlineSpans
            ? setupSpans(a, b, c, viewport, arithmetic, triangle)
            : setupEdges(a, b, c, viewport, arithmetic, fan, triangle)) {
      // Twice the largest clip error, beyond the quarter pixel the candidates' boxes keep.
      const float reach = 2 * std::max({a.clipError, b.clipError, c.clipError});
      triangle.candidateMargin = reach > 0.25f ? static_cast<int>(std::ceil(reach)) : 0;
      out.push_back(triangle);
    } else
      ++stats.empty;
  }
}

}  // namespace

std::vector<SetupTriangle> setupTriangles(const ClipSpaceMesh& mesh, Viewport viewport,
                                          const Arithmetic& arithmetic,
                                          SetupStatistics* statistics) {
  // Blocks of triangles in parallel, concatenated in draw order: the result does not depend on
  // the thread count (the caller's ThreadLimit; on std::threads, every core).
  constexpr size_t kBlock = 2048;
  const size_t triangles = mesh.indices.size() / 3, blocks = (triangles + kBlock - 1) / kBlock;
  std::vector<std::vector<SetupTriangle>> parts(blocks);
  std::vector<SetupStatistics> partStats(blocks);
  parallelFor(blocks, 0, [&](size_t block) {
    for (size_t k = block * kBlock; k < std::min(triangles, (block + 1) * kBlock); ++k)
      setupPrimitive(mesh, k, viewport, arithmetic, parts[block], partStats[block]);
  });
  // Each block's triangles copied to their place in parallel too: a copy of every triangle on one
  // thread was most of a frame's serial time.
  std::vector<size_t> offsets(blocks + 1, 0);
  for (size_t block = 0; block < blocks; ++block)
    offsets[block + 1] = offsets[block] + parts[block].size();
  std::vector<SetupTriangle> result(offsets[blocks]);
  parallelFor(blocks, 0, [&](size_t block) {
    std::copy(parts[block].begin(), parts[block].end(),
              result.begin() + static_cast<std::ptrdiff_t>(offsets[block]));
  });
  SetupStatistics stats;
  for (size_t block = 0; block < blocks; ++block) {
    const SetupStatistics& p = partStats[block];
    stats.triangles += p.triangles;
    stats.nonFinite += p.nonFinite;
    stats.culled += p.culled;
    stats.clipped += p.clipped;
    stats.empty += p.empty;
  }
  if (statistics) *statistics = stats;
  return result;
}

}  // namespace vt::reference
