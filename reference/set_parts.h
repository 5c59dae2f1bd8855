#pragma once
// The pieces a pixel's result set is bounded with (result_set_builder.h): colour bounds, a
// candidate's corners as the model lets them move and what they give (coverage, depth, (s, t)),
// and what the pixels of a block of the oracle's own triangle share. Internal to the oracle's set
// builder (set_builder.h and the set_*.cpp files that define it).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

#include "reference/interval.h"
#include "reference/perturbed_triangle.h"
#include "reference/triangle_setup.h"

namespace vt::reference::sets {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// One unit in the last place of a float in [1, 2).
constexpr double kFloatUlp = 0x1p-23;
// Half of it: the error of one correctly rounded float operation, relative.
constexpr double kRounding = 0x1p-24;
// GLSL 4.50, section 4.7.1: log2 within absolute 2^-21 inside [0.5, 2], 3 ULP outside. Every
// log2 a model allows lies within it, the emulated ones (llvmpipe's polynomial, exact) included.
constexpr double kGlslLog2AbsoluteError = 0x1p-21;
constexpr double kGlslLog2Ulps = 3;
// GL_LINEAR with 8-bit weights: texel positions on a grid of 2^-8 texel (docs/design.md section 7).
constexpr double kFixedPointSubTexelStep = 0x1p-8;
// The trilinear blend's float lerps in the shader, precise: units of 1/255.
constexpr double kBlendRounding = 16 * kFloatUlp * 255;

// Per channel the least and greatest value, in units of 1/255 (channel by channel the operations
// of an Interval, four at a time).
struct Colour {
  glm::dvec4 lo, hi;
};

inline Colour nothing() {
  return {glm::dvec4(std::numeric_limits<double>::infinity()),
          glm::dvec4(-std::numeric_limits<double>::infinity())};
}
inline Colour everyValue() { return {glm::dvec4(0), glm::dvec4(255)}; }
inline Colour hull(const Colour& a, const Colour& b) {
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}
inline Colour widen(const Colour& a, double absolute) { return {a.lo - absolute, a.hi + absolute}; }
// The trilinear blend c0 + (c1 - c0) w = (1 - w) c0 + w c1 of two levels' colours over weights w
// in [0, 1]: it grows with c0 and with c1 (neither weight is negative) and is linear in w, so its
// least value is the least colours' at an end of w and its greatest the greatest colours' (exact
// arithmetic; the callers widen by the blend's rounding).
inline Colour blend(const Colour& c0, const Colour& c1, Interval w) {
  const glm::dvec4 lo0 = c0.lo + (c1.lo - c0.lo) * w.lo, lo1 = c0.lo + (c1.lo - c0.lo) * w.hi;
  const glm::dvec4 hi0 = c0.hi + (c1.hi - c0.hi) * w.lo, hi1 = c0.hi + (c1.hi - c0.hi) * w.hi;
  return {glm::min(lo0, lo1), glm::max(hi0, hi1)};
}

// The least of texels' low values and the greatest of their high ones (a texel's four least
// channel values, then its four greatest), as a Colour.
struct TexelHull {
  std::array<double, 8> bounds{kInfinity,  kInfinity,  kInfinity,  kInfinity,
                               -kInfinity, -kInfinity, -kInfinity, -kInfinity};
  void include(const std::array<double, 8>& v) {
    for (size_t k = 0; k < 4; ++k) bounds[k] = std::min(bounds[k], v[k]);
    for (size_t k = 4; k < 8; ++k) bounds[k] = std::max(bounds[k], v[k]);
  }
  Colour colour() const {
    return {{bounds[0], bounds[1], bounds[2], bounds[3]},
            {bounds[4], bounds[5], bounds[6], bounds[7]}};
  }
};

// Along one axis of a box of texel positions, where the bilinear filter's bounds over it may lie:
// the box's ends and the texel centres (at + 0.5) strictly inside, where the cells between centres
// meet (on each cell the filter is bilinear). At most N of them.
template <size_t N>
struct Stops {
  std::array<double, N> at;
  size_t count = 0;
  // False when there are more than fit.
  bool of(Interval v) {
    at[count++] = v.lo;
    for (double k = std::ceil(v.lo - 0.5) + 0.5; k < v.hi; k += 1)
      if (k > v.lo) {
        if (count == N - 1) return false;
        at[count++] = k;
      }
    at[count++] = v.hi;
    return true;
  }
};

// The corners of a triangle as boxes: each within `radius` pixels (the model's snapping) plus the

// viewport's size) of its float window position, plus, for a corner the clipper made, twice what
// the float clipping moved it (WindowCorner::clipError).
struct CornerBoxes {
  std::array<Interval, 3> x, y;
};
CornerBoxes cornerBoxes(const SetupTriangle& t, double radius, Viewport viewport);
// The largest radius of the boxes: what PerturbedTriangle lets every corner move by.
double largestRadius(const CornerBoxes& b);

// Barycentric coordinates as affine functions of the window position: lambda_i(p) = e_i(p) / a
// with e_i the edge function opposite corner i and a twice the signed area (the same sign, so
// lambda does not depend on the orientation).
struct Barycentrics {
  std::array<Interval, 3> atCentre, ddx, ddy;  // at the pixel centre of the query, and per pixel
  bool degenerate = false;                     // the area may be zero
};
Barycentrics barycentrics(const CornerBoxes& b, double cx, double cy);

// A candidate's corners as the model lets them move: boxes for the interval bounds, and the
// first-order bounds where the triangle is large enough for them (perturbed_triangle.h). Made once
// per candidate and pixel, for its coverage, depth and fragment.
struct Snapped {
  CornerBoxes boxes;
  PerturbedTriangle perturbed;
  AffinePlane s, t;  // the planes through the corners' s/w and t/w (when perturbed is bounded)

  // The fine steps of s and t from one pixel centre along one axis (PerturbedTriangle::ratioStep):
  // a quad's two pixels of a row step from the same left centre, those of a column from the same
  // lower one, so the two latest per axis serve the next pixels of the quad.
  struct Steps {
    double x = kNaN, y = 0;
    Interval s, t;
  };
  std::array<std::array<Steps, 2>, 2> steps;  // [axis][slot]
  std::array<uint8_t, 2> nextSlot{};
  // Where the last pixel centre asked for maps from (PerturbedTriangle::sourceBox): its
  // coverage, depth and fragment all start there.
  double sourceX = kNaN, sourceY = 0;
  WindowBox source;

  const WindowBox& sourceAt(double cx, double cy) {
    if (cx != sourceX || cy != sourceY) {
      source = perturbed.sourceBox(cx, cy);
      sourceX = cx;
      sourceY = cy;
    }
    return source;
  }

  const Steps& stepsFrom(double x, double y, int axis) {
    auto& kept = steps[static_cast<size_t>(axis)];
    for (const Steps& k : kept)
      if (k.x == x && k.y == y) return k;
    Steps& slot = kept[nextSlot[static_cast<size_t>(axis)]];
    nextSlot[static_cast<size_t>(axis)] ^= 1;
    const std::array<Interval, 2> st = perturbed.ratioSteps(s, t, x, y, axis);
    slot = {x, y, st[0], st[1]};
    return slot;
  }
};

// Whether a set-up triangle covers a pixel centre: 2 surely, 1 possibly, 0 not. A piece of a
// clipped fan that is possible only because the centre may lie on the far side of edges shared
// with its neighbours (openFanEdges, bit i: the edge opposite corner i) is surely inside the mesh
// triangle's own edges (boundarySure); appendResultSet decides the fan's union from its pieces.
struct PieceCoverage {
  int cover = 0;
  uint8_t openFanEdges = 0;
  bool boundarySure = true;
};

// What a candidate is over the kBlock x kBlock pixels of the block that holds a pixel, decided once
// per block from a box that holds every centre's source box (PerturbedTriangle::sourceBoxOver):
// the interval bounds over it hold those over each centre's, so its decisions are each pixel's.
struct BlockClass {
  int32_t index = -1;
  // 0: surely covers no centre; 2: surely every centre; -1: pixel by pixel; -2: not classed yet.
  int8_t cover = -2;
  Interval z = Interval::everything();  // what depth() bounds at every centre
  Snapped* snapped = nullptr;           // Builder::snapped's, where the class was made from it
};

// An interpolated plane: value at a pixel and change per pixel in x and y.
struct PlaneRange {
  Interval value, ddx, ddy;
};

inline PlaneRange interpolate(const Barycentrics& l, float a0, float a1, float a2) {
  const double a[3] = {a0, a1, a2};
  PlaneRange r;
  for (size_t i = 0; i < 3; ++i) {
    r.value = r.value + l.atCentre[i] * a[i];
    r.ddx = r.ddx + l.ddx[i] * a[i];
    r.ddy = r.ddy + l.ddy[i] * a[i];
  }
  return {widen(r.value), widen(r.ddx), widen(r.ddy)};
}

// n / d at a pixel, and the fine derivative (n + dn) / (d + dd) - n / d = (dn d - n dd) / (d (d +
// dd)) of the same planes, so that the two values' errors stay correlated.
inline Interval ratio(Interval n, Interval d) { return widen(n / d); }
inline Interval ratioStep(Interval n, Interval d, Interval dn, Interval dd) {
  return widen((dn * d - n * dd) / (d * (d + dd)));
}

// The interval of a plane moved to pixel (px + dx, py + dy) from the query pixel.
inline PlaneRange moved(const PlaneRange& p, int dx, int dy) {
  return {widen(p.value + p.ddx * dx + p.ddy * dy), p.ddx, p.ddy};
}

// A fine derivative whose two values each differ by `relative` of their size (at least `scale`)
// plus a float rounding: the difference by the sum of both.
[[gnu::always_inline]] inline Interval floatStep(Interval v, double scale, double relative) {
  const double size = 2 * (scale + v.magnitude()) + v.magnitude();
  return widen(v, 0, (relative + kFloatUlp) * size);
}

// Everything the shader computes of one candidate at one pixel, as intervals.
struct FragmentRange {
  Interval s, t;  // after the clamp
  Interval lod;
  bool everything = false;  // a w near zero: any (s, t) and any level
};

// per block and triangle (Builder::ownAlternative). With B the box that holds every centre's
// source box (PerturbedTriangle::sourceBoxOver), rho its margin around the centres, and, for
// f = s or t, bounds over B grown by the step radius of |f| and of its gradient (g_x, g_y)
// (PerturbedTriangle::ratioOver):
//   - f at a centre p: the moved triangle's value is the nominal one at a point of p's source box,
//     within (g_x + g_y) rho of the nominal f(p); plus the model's float error relative to the
//     scale, as fragment() counts it. This bounds every pixel's (s, t) in the block, hence what
//     the block reads on each level;
//   - per level, the texels the block's (s, t) reach there, inside one page (LevelBounds).
// A pixel takes its own, tighter widths (PerturbedTriangle::ratioReach and ratioStepReach, from
// its own and its steps' source boxes; the value's at most the block's, so that it stays in
// reach), and per level the filter's range over its own texel box from the kept texels
// (Builder::localFilter).

// How a page of level m maps (s, t) to cache texel positions through its indirection entry (the
// page itself or its resident ancestor, level i, at `origin` in the cache):
//   x = origin.x + (s 2^i - resident.x) pageSize, alike for y.
struct PageMap {
  glm::dvec2 origin{0};
  glm::ivec2 resident{0};
  double scale = 1;  // 2^i
  int pageSize = 0;
  Interval x(Interval s) const { return along(s, origin.x, resident.x); }
  Interval y(Interval t) const { return along(t, origin.y, resident.y); }
  Interval along(Interval v, double o, int r) const {
    return {o + (v.lo * scale - r) * pageSize, o + (v.hi * scale - r) * pageSize};
  }
};

// Level m of the cache as an OwnBlock's (s, t) reach it: the texels a bilinear sample anywhere in
// reach reads, kept for the block's pixels (Builder::localFilter).
struct LevelBounds {
  int8_t state = 0;          // 0: not made yet; 1: bounded; -1: two pages or too many texels
  PageMap map;               // of the page the reach lies on
  double positionError = 0;  // the sampler's (Builder::samplerErrors)
  glm::ivec2 origin{0};      // the first texel kept
  int width = 0, height = 0;
  size_t offset = 0;  // of its texels in OwnBlock::texels, row by row
};

// The bilinear filter over a box of texel positions on one level: per channel the largest
// difference of neighbouring texels along x and along y among those it reads (its Lipschitz
// constants there, in units of 1/255 per texel: on each cell the filter's slope is a convex
// combination of its two rows' or columns' differences) and their least and greatest values (its
// range there).
struct LocalFilter {
  glm::dvec4 lipschitzX{0}, lipschitzY{0};
  glm::dvec4 rounding{0};  // the corner-weight sampler's rounding on these cells (cornerRounding)
  Colour range;            // the filter's least and greatest value over the box
  glm::dvec4 at{0};        // its value at the box's centre
};

struct OwnBlock {
  int32_t index = -1;
  bool bounded = false;
  AffinePlane w;  // 1/w; per attribute (s, t) its numerator plane and f_x = (ax + cross y) / w^2,
                  // f_y = (ay - cross x) / w^2
  std::array<AffinePlane, 2> n;
  std::array<double, 2> ax{}, ay{}, cross{};
  std::array<double, 2> value{};  // a set's s (t) within this of the nominal value at any centre
  // What a pixel adds to its own widths (ratioReach, ratioStepReach from a source box reaching
  // at most rho): the model's float error of a value (floatError) and of a difference (relative
  // to scale), and the rounding of a step's middle derivative in double.
  double rho = 0, relative = 0;
  std::array<double, 2> scale{}, rounding{}, floatError{};
  Interval sReach, tReach;          // every (s, t) of a set in the block, clamped to [0, 1]
  double valueError = 0;            // a bilinear sample's (Builder::samplerErrors)
  std::vector<LevelBounds> levels;  // by level, each made when a pixel first needs it
  std::vector<glm::u8vec4> texels;  // the levels' texels
};

// What ownAlternative bounds of a pixel's colour from its block's levels: every colour a set
// admits, and the filter's share alone (centre plus or minus filter per channel, units of 1/255).
struct OwnColour {
  Colour colour;
  glm::dvec4 centre{0}, filter{0};
};

// 2^m for a level m (0 to 31), exact.
inline double powerOfTwo(int m) { return static_cast<double>(uint64_t{1} << m); }

inline int floorToInt(double x, int hi) {
  if (!(x >= 0)) return 0;
  return static_cast<int>(std::min<double>(std::floor(x), hi));
}

struct PixelCandidate {
  int32_t index;
  Snapped* snapped;  // when the model moves vertices
  PieceCoverage piece;
  Interval z;
  int cover;  // of the mesh triangle: the piece's, or 2 where its fan surely covers
};

}  // namespace vt::reference::sets
