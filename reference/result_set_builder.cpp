#include "reference/result_set_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "format/page_address.h"
#include "reference/framebuffer_conversion.h"
#include "reference/interval.h"
#include "reference/perturbed_triangle.h"
#include "shader/shader_cpp.h"

namespace vt::reference {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// One unit in the last place of a float in [1, 2).
constexpr double kFloatUlp = 0x1p-23;
// Half of it: the error of one correctly rounded float operation, relative.
constexpr double kRounding = 0x1p-24;
// GLSL 4.50, section 4.7.1: log2 within absolute 2^-21 inside [0.5, 2], 3 ULP outside. Every
// log2 a model allows lies within it, the emulated ones (llvmpipe's polynomial, exact) included.
constexpr double kGlslLog2AbsoluteError = 0x1p-21;
constexpr double kGlslLog2Ulps = 3;
// GL_LINEAR with 8-bit weights: texel positions on a grid of 2^-8 texel (DESIGN section 7).
constexpr double kFixedPointSubTexelStep = 0x1p-8;
// The trilinear blend's float lerps in the shader, precise: units of 1/255.
constexpr double kBlendRounding = 16 * kFloatUlp * 255;

// Per channel the least and greatest value, in units of 1/255 (channel by channel the operations
// of an Interval, four at a time).
struct Colour {
  glm::dvec4 lo, hi;
};

Colour nothing() {
  return {glm::dvec4(std::numeric_limits<double>::infinity()),
          glm::dvec4(-std::numeric_limits<double>::infinity())};
}
Colour everyValue() { return {glm::dvec4(0), glm::dvec4(255)}; }
Colour hull(const Colour& a, const Colour& b) {
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}
Colour widen(const Colour& a, double absolute) { return {a.lo - absolute, a.hi + absolute}; }
// The trilinear blend c0 + (c1 - c0) w = (1 - w) c0 + w c1 of two levels' colours over weights w
// in [0, 1]: it grows with c0 and with c1 (neither weight is negative) and is linear in w, so its
// least value is the least colours' at an end of w and its greatest the greatest colours' (exact
// arithmetic; the callers widen by the blend's rounding).
Colour blend(const Colour& c0, const Colour& c1, Interval w) {
  const glm::dvec4 lo0 = c0.lo + (c1.lo - c0.lo) * w.lo, lo1 = c0.lo + (c1.lo - c0.lo) * w.hi;
  const glm::dvec4 hi0 = c0.hi + (c1.hi - c0.hi) * w.lo, hi1 = c0.hi + (c1.hi - c0.hi) * w.hi;
  return {glm::min(lo0, lo1), glm::max(hi0, hi1)};
}

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
// float error of its window transform (x / w * W / 2 + W / 2: a few roundings of values up to the
// viewport's size) of its float window position, plus, for a corner the clipper made, twice what
// the float clipping moved it (WindowCorner::clipError).
struct CornerBoxes {
  std::array<Interval, 3> x, y;
};

CornerBoxes cornerBoxes(const SetupTriangle& t, double radius, Viewport viewport) {
  CornerBoxes b;
  const double extent = std::max(viewport.width, viewport.height);
  for (size_t i = 0; i < 3; ++i) {
    const double window =
        4 * kFloatUlp * (std::fabs(t.corners[i].x) + std::fabs(t.corners[i].y) + extent);
    const double clipped = 2.0 * t.corners[i].clipError;
    b.x[i] = Interval::around(t.corners[i].x, radius + window + clipped);
    b.y[i] = Interval::around(t.corners[i].y, radius + window + clipped);
  }
  return b;
}

// The largest radius of the boxes: what PerturbedTriangle lets every corner move by.
double largestRadius(const CornerBoxes& b) {
  double r = 0;
  for (size_t i = 0; i < 3; ++i) r = std::max({r, b.x[i].width() / 2, b.y[i].width() / 2});
  return r;
}

// Barycentric coordinates as affine functions of the window position: lambda_i(p) = e_i(p) / a
// with e_i the edge function opposite corner i and a twice the signed area (the same sign, so
// lambda does not depend on the orientation).
struct Barycentrics {
  std::array<Interval, 3> atCentre, ddx, ddy;  // at the pixel centre of the query, and per pixel
  bool degenerate = false;                     // the area may be zero
};

Barycentrics barycentrics(const CornerBoxes& b, double cx, double cy) {
  Barycentrics r;
  const Interval area =
      (b.x[1] - b.x[0]) * (b.y[2] - b.y[0]) - (b.x[2] - b.x[0]) * (b.y[1] - b.y[0]);
  if (area.containsZero()) {
    r.degenerate = true;
    return r;
  }
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3, k = (i + 2) % 3;
    // e_i(p) = (x_k - x_j) (p_y - y_j) - (y_k - y_j) (p_x - x_j)
    const Interval e = (b.x[k] - b.x[j]) * (Interval::point(cy) - b.y[j]) -
                       (b.y[k] - b.y[j]) * (Interval::point(cx) - b.x[j]);
    r.atCentre[i] = widen(e / area);
    r.ddx[i] = widen(-(b.y[k] - b.y[j]) / area);
    r.ddy[i] = widen((b.x[k] - b.x[j]) / area);
  }
  return r;
}

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

PlaneRange interpolate(const Barycentrics& l, float a0, float a1, float a2) {
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
Interval ratio(Interval n, Interval d) { return widen(n / d); }
Interval ratioStep(Interval n, Interval d, Interval dn, Interval dd) {
  return widen((dn * d - n * dd) / (d * (d + dd)));
}

// The interval of a plane moved to pixel (px + dx, py + dy) from the query pixel.
PlaneRange moved(const PlaneRange& p, int dx, int dy) {
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

// The oracle's own triangle over one 4 x 4 block: what its pixels' alternatives share, made once
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
  Colour range;      // the filter's least and greatest value over the box
  glm::dvec4 at{0};  // its value at the box's centre
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

// 2^m for a level m (0 to 31), exact.
double powerOfTwo(int m) { return static_cast<double>(uint64_t{1} << m); }

int floorToInt(double x, int hi) {
  if (!(x >= 0)) return 0;
  return static_cast<int>(std::min<double>(std::floor(x), hi));
}

class Builder {
 public:
  Builder(const PrecisionModel& model, const SetShading& shading, Viewport viewport,
          TexelSource& source)
      : model_(model), shading_(shading), viewport_(viewport), source_(source) {
    finestSide_ = std::ldexp(
        static_cast<double>(shading.pageSize) * static_cast<double>(1 << shading.finestLevel),
        -shading.needScaleLog2);
    subTexelStep_ = std::ldexp(1.0, -model.subTexelBits);
    if (const Filter& f = model.arithmetic.filter; !shading.exactFilter && model.filterPinned &&
                                                   f.weights == FilterWeights::kFixedPointCorners)
      cornerStep_ = std::ldexp(f.lerpRounding == LerpRounding::kNearest ? 0.5 : 1.0, -f.weightBits);
  }

  // Whether the model lets vertices move at all (else coverage, depth and attributes are the
  // oracle's own values and nothing needs a Snapped).
  bool movesVertices() const {
    return !model_.coveragePinned() || model_.depthUlps != 0 || !model_.depthRoundsToNearest ||
           model_.attributeUlps != 0;
  }

  // Candidate `index`'s moved corners, made once per builder (a tile's pixels share them); null
  // when the model moves no vertex.
  Snapped* snapped(const SetupTriangle& t, int32_t index) {
    if (!movesVertices()) return nullptr;
    const auto found = snapped_.find(index);
    if (found != snapped_.end()) return &found->second;
    const CornerBoxes boxes = cornerBoxes(t, snapRadius(), viewport_);
    const PerturbedTriangle perturbed(t, largestRadius(boxes));
    AffinePlane s, tt;
    if (perturbed.bounded()) {
      s = perturbed.attribute({t.corners[0].sw, t.corners[1].sw, t.corners[2].sw});
      tt = perturbed.attribute({t.corners[0].tw, t.corners[1].tw, t.corners[2].tw});
    }
    return &snapped_.emplace(index, Snapped{boxes, perturbed, s, tt, {}, {}, kNaN, 0, {}})
                .first->second;
  }

  // The classes over the block from (bx, by) of its candidates (`count` of them), by their
  // position in its list, each made by the first pixel that asks (cover unknown before). The
  // blocks of a quad row of a tile are visited in turns, so one slot per block column is kept.
  std::vector<BlockClass>& blockClasses(int bx, int by, size_t count) {
    constexpr int kBlock = Visibility::kBlock;
    BlockSlot& slot = blocks_[static_cast<size_t>((bx / kBlock) % kBlockSlots)];
    if (slot.x != bx || slot.y != by || slot.classes.size() != count) {
      slot.x = bx;
      slot.y = by;
      slot.classes.assign(count, BlockClass{});
      slot.ownCount = 0;
    }
    return slot.classes;
  }

  // The OwnBlock of candidate `index` over the block from (bx, by), made by the first pixel that
  // asks (blockClasses has set the block's slot).
  OwnBlock& ownBlock(int32_t index, const Snapped& snapped, int bx, int by) {
    constexpr int kBlock = Visibility::kBlock;
    BlockSlot& slot = blocks_[static_cast<size_t>((bx / kBlock) % kBlockSlots)];
    for (size_t k = 0; k < slot.ownCount; ++k)
      if (slot.own[k].index == index) return slot.own[k];
    if (slot.ownCount == slot.own.size()) slot.own.emplace_back();
    OwnBlock& b = slot.own[slot.ownCount++];
    makeOwnBlock(index, snapped, bx, by, b);
    return b;
  }

  // The oracle's own alternative at (px, py), candidate `index` (the oracle's triangle there), from
  // its block's widths (OwnBlock): false where the block has none.
  bool ownAlternative(const SetupTriangle& t, int32_t index, const Snapped& snapped, int px, int py,
                      const OracleFragment& oracle, Alternative& a) {
    constexpr int kBlock = Visibility::kBlock;
    OwnBlock& b = ownBlock(index, snapped, px - px % kBlock, py - py % kBlock);
    if (!b.bounded) return false;
    // Where the oracle sampled: inside what the block's level bounds were made over.
    const double so = std::clamp<double>(oracle.uv.x, 0, 1);
    const double to = std::clamp<double>(oracle.uv.y, 0, 1);
    if (!b.sReach.contains(so) || !b.tReach.contains(to)) return false;
    const double cx = px + 0.5, cy = py + 0.5;
    const double w = b.w.at(cx, cy);
    const double sNominal = b.n[0].at(cx, cy) / w, tNominal = b.n[1].at(cx, cy) / w;
    // The steps' middles: the quad's row's from its left centre, its column's from its lower.
    const double mx = (px & ~1) + 1.0, my = (py & ~1) + 1.0;
    const double wx = b.w.at(mx, cy), wy = b.w.at(cx, my);
    const double wx2 = wx * wx, wy2 = wy * wy;
    // How far the pixel's, its quad row's left and its quad column's lower source boxes reach
    // around their centres (PerturbedTriangle::sourceBox; at most the block's rho).
    const PerturbedTriangle& moves = snapped.perturbed;
    const auto reach = [&](double x, double y) {
      return std::min(b.rho, (moves.sourceBox(x, y).x.hi - x) * (1 + 0x1p-40));
    };
    const double rho = reach(cx, cy), rhoLeft = reach(mx - 0.5, cy), rhoLower = reach(cx, my - 0.5);
    std::array<Interval, 4> d;  // ds/dx, dt/dx, ds/dy, dt/dy
    std::array<double, 2> value;  // how far a set's s and t lie from the nominal values
    for (size_t k = 0; k < 2; ++k) {
      const double slopeX = (b.ax[k] + b.cross[k] * cy) / wx2;
      const double slopeY = (b.ay[k] - b.cross[k] * cx) / wy2;
      d[k] = Interval::around(slopeX, stepWidth(b, moves, k, 0, mx - 0.5, cy, rhoLeft));
      d[k + 2] = Interval::around(slopeY, stepWidth(b, moves, k, 1, cx, my - 0.5, rhoLower));
      value[k] = std::min(b.value[k], moves.ratioReach(b.n[k], cx, cy, rho) + b.floatError[k]);
    }
    const Interval lod = hull(lodRange(d[0], d[1], d[2], d[3]), Interval::point(oracle.lod));
    const int L = shading_.finestLevel;
    // The blends from level `first` to `top` (trilinear: each with the next finer level).
    const int first = std::clamp(static_cast<int>(std::floor(lod.lo)), 0, L);
    const int top = std::clamp(static_cast<int>(std::floor(lod.hi)), first, L);
    const int last = std::min(top + 1, L);
    // The set's (s, t), as the shader samples them: clamped to [0, 1].
    const Interval s =
        clamp(hull(Interval::around(sNominal, value[0]), Interval::point(oracle.uv.x)), 0, 1);
    const Interval tt =
        clamp(hull(Interval::around(tNominal, value[1]), Interval::point(oracle.uv.y)), 0, 1);
    // Per level the LOD reaches, the filter over every texel position a set admits (those of its
    // (s, t) box, within the sampler's position error); and over the oracle's position alone, as
    // the Lipschitz bound of the sampler's position error.
    std::array<Colour, kMaxLevel + 1> range;  // (finestLevel <= kMaxLevel: format/page_address.h)
    // The exact filter at the oracle's (s, t) on the two levels its LOD blends.
    const double oracleLod = std::clamp<double>(oracle.lod, 0, L);
    const int oracleCoarse = std::min(static_cast<int>(std::floor(oracleLod)), L);
    std::array<glm::dvec4, 2> atOracle{};
    glm::dvec4 own(0);
    for (int m = first; m <= last; ++m) {
      const LevelBounds& l = levelBounds(b, m);
      if (l.state < 0) return false;
      const glm::dvec2 at(l.map.x(Interval::point(so)).lo, l.map.y(Interval::point(to)).lo);
      const WindowBox box{widen(l.map.x(s), 0, l.positionError),
                          widen(l.map.y(tt), 0, l.positionError)};
      LocalFilter here;
      if (!localFilter(b, l, box, at, here)) return false;
      range[static_cast<size_t>(m)] = {here.range.lo - here.rounding - b.valueError,
                                       here.range.hi + here.rounding + b.valueError};
      if (m == oracleCoarse || m == oracleCoarse + 1)
        atOracle[static_cast<size_t>(m - oracleCoarse)] = here.at;
      own = glm::max(own, (here.lipschitzX + here.lipschitzY) * l.positionError + here.rounding);
    }
    // The trilinear blend of neighbouring levels over the LOD's weights, as shade() blends.
    Colour colour = nothing();
    for (int coarse = first; coarse <= top; ++coarse) {
      const Colour& c0 = range[static_cast<size_t>(coarse)];
      if (coarse == L) {
        colour = hull(colour, c0);
        continue;
      }
      const Colour& c1 = range[static_cast<size_t>(coarse) + 1];
      colour = hull(colour, blend(c0, c1, clamp(Interval{lod.lo - coarse, lod.hi - coarse}, 0, 1)));
    }
    colour = widen(colour, kBlendRounding);
    // The filter alone: the exact filter at the oracle's (s, t) and LOD, within the sampler's
    // position error's change, its value error and the blend's rounding.
    const glm::dvec4 centre =
        oracleCoarse == L ? atOracle[0]
                          : atOracle[0] + (atOracle[1] - atOracle[0]) * (oracleLod - oracleCoarse);
    const glm::dvec4 filter = own + b.valueError + kBlendRounding;
    a.triangle = static_cast<int32_t>(t.primitive);
    a.levelLo = static_cast<uint8_t>(
        std::min(std::clamp(static_cast<int>(std::ceil(lod.lo)), 0, L), oracle.neededLevel));
    a.levelHi = static_cast<uint8_t>(
        std::max(std::clamp(static_cast<int>(std::ceil(lod.hi)), 0, L), oracle.neededLevel));
    setUv(s, tt, a);
    a.uvLo = glm::min(a.uvLo, oracle.uv);
    a.uvHi = glm::max(a.uvHi, oracle.uv);
    store(colour, a.colorLo, a.colorHi);
    store({centre - filter, centre + filter}, a.filterLo, a.filterHi);
    a.filterLo = glm::min(a.filterLo, oracle.color);
    a.filterHi = glm::max(a.filterHi, oracle.color);
    a.colorLo = glm::min(a.colorLo, a.filterLo);
    a.colorHi = glm::max(a.colorHi, a.filterHi);
    return true;
  }

  // Candidate `index`'s class over the block from (bx, by); its pixels decide alone (cover -1, any
  // depth) under pinned coverage and for triangles too small for first-order bounds.
  BlockClass blockClass(const SetupTriangle& t, int32_t index, int bx, int by, DepthFormat format) {
    constexpr int kBlock = Visibility::kBlock;
    BlockClass c;
    c.index = index;
    c.cover = -1;
    if (model_.coveragePinned()) return c;
    Snapped* s = c.snapped = snapped(t, index);
    if (!s->perturbed.bounded()) return c;
    const WindowBox box =
        s->perturbed.sourceBoxOver(bx + 0.5, by + 0.5, bx + kBlock - 0.5, by + kBlock - 0.5);
    c.cover = 2;
    for (size_t i = 0; i < 3 && c.cover != 0; ++i) {
      const Interval lambda = s->perturbed.barycentric(i, box);
      if (lambda.hi < 0)
        c.cover = 0;
      else if (!(lambda.lo > 0))
        c.cover = -1;
    }
    if (c.cover != 0) {
      // What depth() bounds at each centre: its steps over the block's box instead of a centre's
      // source box, with the arithmetic's own window depth at every centre of the block.
      Interval own = {std::numeric_limits<double>::infinity(),
                      -std::numeric_limits<double>::infinity()};
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x)
          own = hull(own, Interval::point(windowDepth(t, x, y, model_.arithmetic)));
      double planeTerms = 0;
      for (const double cx : {bx + 0.5, bx + kBlock - 0.5})
        for (const double cy : {by + 0.5, by + kBlock - 0.5})
          planeTerms = std::max(planeTerms, s->perturbed.depthTerms(cx, cy));
      const Interval z =
          widen(s->perturbed.depth(box), 0,
                depthError(t, planeTerms, [&] { return s->perturbed.barycentrics(box); }));
      c.z = depthStored(hull(z, own), format);
    }
    return c;
  }

  // The depth error of candidate t beyond moved corners, in depth units, at a centre (or over a
  // box) where the window plane's terms are at most `planeTerms` and `lambda()` gives the
  // barycentric coordinates. The model's depthUlps and the oracle's own rounding each count 2^-23
  // of the largest of: the depth range [0, 1]; the terms the window plane's evaluation sums
  // (PerturbedTriangle::depthTerms); and the terms any computation of the corners' window z sums,
  // interpolated (WindowCorner::depthTerms). A float evaluation errs relative to its terms, not
  // to the value they sum to, and a corner clipped from a vertex behind the camera is a small
  // difference of huge terms: an H100, which draws such a triangle as the exact polygon, showed a
  // ground plane 2 x 10^5 wide in front of a triangle that is nearer by 3,900 units of 2^-23
  // (data/gpus/nvidia-h100/README.md). Added: a corner the oracle's clipper made moves twice its
  // own float clipping's depth error, by its weight. Infinite where nothing is bounded.
  template <typename BarycentricsOf>
  double depthError(const SetupTriangle& t, double planeTerms, BarycentricsOf lambda) const {
    double scale = std::max(1.0, planeTerms);
    double clipped = 0;
    const std::array<WindowCorner, 3>& c = t.corners;
    // A corner within the depth range has terms of at most 1, so its share never passes the range.
    if (std::max({c[0].depthTerms, c[1].depthTerms, c[2].depthTerms}) > 1 ||
        std::max({c[0].clipDepthError, c[1].clipDepthError, c[2].clipDepthError}) > 0) {
      const std::array<Interval, 3> l = lambda();
      double cornerTerms = 0;
      for (size_t j = 0; j < 3; ++j) {
        cornerTerms += c[j].depthTerms * l[j].magnitude();
        clipped += 2.0 * c[j].clipDepthError * l[j].magnitude();
      }
      scale = std::max(scale, cornerTerms);
    }
    const double error = (model_.depthUlps + 1) * kFloatUlp * scale + clipped;
    return std::isfinite(error) ? error : std::numeric_limits<double>::infinity();
  }

  // Coverage of candidate t at the centre of (px, py); `s` is needed unless coverage is pinned.
  PieceCoverage coverage(const SetupTriangle& t, Snapped* s, int px, int py) const {
    if (model_.coveragePinned()) return {t.covers(px, py) ? 2 : 0};
    std::array<Interval, 3> lambda;
    if (s->perturbed.bounded()) {
      // Each coordinate only while none so far is surely negative (most candidates are outside).
      const WindowBox& source = s->sourceAt(px + 0.5, py + 0.5);
      for (size_t i = 0; i < 3; ++i) {
        lambda[i] = s->perturbed.barycentric(i, source);
        if (lambda[i].hi < 0) return {0};
      }
    } else {
      const Barycentrics l = barycentrics(s->boxes, px + 0.5, py + 0.5);
      if (l.degenerate) return {1};
      lambda = l.atCentre;
    }
    PieceCoverage c{2};
    for (size_t i = 0; i < 3; ++i) {
      // Surely outside any edge: not this piece. Beyond an edge inside a clipped fan lies the
      // fan's next piece, a candidate of its own with the same planes.
      if (lambda[i].hi < 0) return {0};
      if (lambda[i].lo > 0) continue;
      // On the centre's side or not: the tie rule decides on an edge of the mesh triangle; on an
      // edge inside the fan the pixel is this piece's or its neighbour's (appendResultSet).
      c.cover = 1;
      if (t.fanNeighbour[i] != 0)
        c.openFanEdges = static_cast<uint8_t>(c.openFanEdges | (1u << i));
      else
        c.boundarySure = false;
    }
    return c;
  }

  // Window depth of candidate t at (px, py) as the depth test compares it.
  Interval depth(const SetupTriangle& t, Snapped* s, int px, int py, DepthFormat format) const {
    const double own = windowDepth(t, px, py, model_.arithmetic);
    if (depthPinned()) return Interval::point(own);
    const PerturbedTriangle& perturbed = s->perturbed;
    const Barycentrics l =
        perturbed.bounded() ? Barycentrics{} : barycentrics(s->boxes, px + 0.5, py + 0.5);
    Interval z = Interval::everything();
    if (perturbed.bounded() || !l.degenerate) {
      const WindowBox source = perturbed.bounded() ? s->sourceAt(px + 0.5, py + 0.5) : WindowBox{};
      z = perturbed.bounded()
              ? perturbed.depth(source)
              : interpolate(l, t.corners[0].z, t.corners[1].z, t.corners[2].z).value;
      const double error = depthError(t, perturbed.depthTerms(px + 0.5, py + 0.5), [&] {
        return perturbed.bounded() ? perturbed.barycentrics(source) : l.atCentre;
      });
      z = std::isfinite(error) ? widen(z, 0, error) : Interval::everything();
    }
    return depthStored(hull(z, Interval::point(own)), format);
  }

  FragmentRange fragment(const SetupTriangle& t, Snapped* snapped, int px, int py) const {
    const int qx = px & ~1, qy = py & ~1;
    const int column = px - qx, row = py - qy;
    const bool attributesPinned = model_.attributeUlps == 0 && model_.coveragePinned();
    FragmentRange f;
    Interval dsdx, dtdx, dsdy, dtdy;
    if (attributesPinned) {
      // The oracle's own float values at the quad's pixels (renderer.cpp computes them alike).
      const auto at = [&](int x, int y) { return attributesAt(t, x, y, model_.arithmetic).uv; };
      const glm::vec2 here = at(px, py);
      const glm::vec2 dx = at(qx + 1, qy + row) - at(qx, qy + row);
      const glm::vec2 dy = at(qx + column, qy + 1) - at(qx + column, qy);
      f.s = Interval::point(here.x);
      f.t = Interval::point(here.y);
      dsdx = Interval::point(dx.x);
      dtdx = Interval::point(dx.y);
      dsdy = Interval::point(dy.x);
      dtdy = Interval::point(dy.y);
      if (!std::isfinite(here.x) || !std::isfinite(here.y)) f.everything = true;
    } else {
      const PerturbedTriangle& perturbed = snapped->perturbed;
      const Barycentrics l =
          perturbed.bounded() ? Barycentrics{} : barycentrics(snapped->boxes, px + 0.5, py + 0.5);
      const double relative = model_.attributeUlps * kFloatUlp;
      if (perturbed.bounded()) {
        const AffinePlane& s = snapped->s;
        const AffinePlane& tt = snapped->t;
        const double cx = px + 0.5, cy = py + 0.5, lx = qx + 0.5, by = qy + 0.5;
        // The model's float error is relative to the size of the terms the evaluation sums
        // (perturbed_triangle.h), at least the value's.
        const std::array<double, 2> scales = perturbed.ratioScales(s, tt, cx, cy);
        const double sScale = scales[0], tScale = scales[1];
        const std::array<Interval, 2> here = perturbed.ratios(s, tt, snapped->sourceAt(cx, cy));
        const Interval sHere = here[0], tHere = here[1];
        f.s = widen(sHere, 0, relative * std::max(sScale, sHere.magnitude()) + kFloatUlp);
        f.t = widen(tHere, 0, relative * std::max(tScale, tHere.magnitude()) + kFloatUlp);
        // Fine derivatives: from the left pixel of the quad row, from the lower of its column.
        const Snapped::Steps& alongX = snapped->stepsFrom(lx, cy, 0);
        const Snapped::Steps& alongY = snapped->stepsFrom(cx, by, 1);
        dsdx = floatStep(alongX.s, std::max(sScale, sHere.magnitude()), relative);
        dtdx = floatStep(alongX.t, std::max(tScale, tHere.magnitude()), relative);
        dsdy = floatStep(alongY.s, std::max(sScale, sHere.magnitude()), relative);
        dtdy = floatStep(alongY.t, std::max(tScale, tHere.magnitude()), relative);
        if (!f.s.finite() || !f.t.finite() || !dsdx.finite() || !dtdx.finite() || !dsdy.finite() ||
            !dtdy.finite())
          f.everything = true;
      } else if (l.degenerate) {
        f.everything = true;
      } else {
        const PlaneRange w = interpolate(l, t.corners[0].oow, t.corners[1].oow, t.corners[2].oow);
        const PlaneRange s = interpolate(l, t.corners[0].sw, t.corners[1].sw, t.corners[2].sw);
        const PlaneRange tt = interpolate(l, t.corners[0].tw, t.corners[1].tw, t.corners[2].tw);
        f.s = widen(ratio(s.value, w.value), relative, kFloatUlp);
        f.t = widen(ratio(tt.value, w.value), relative, kFloatUlp);
        // Fine derivatives: the left pixel of the quad row, the lower of the quad column.
        const PlaneRange wl = moved(w, qx - px, 0), sl = moved(s, qx - px, 0),
                         tl = moved(tt, qx - px, 0);
        const PlaneRange wb = moved(w, 0, qy - py), sb = moved(s, 0, qy - py),
                         tb = moved(tt, 0, qy - py);
        // Each of the two values differs by `relative` of its size; their difference by the sum.
        const auto step = [&](Interval n, Interval d, Interval dn, Interval dd) {
          const Interval v = ratioStep(n, d, dn, dd);
          const double size = 2 * ratio(n, d).magnitude() + v.magnitude();
          return widen(v, 0, (relative + kFloatUlp) * size);
        };
        dsdx = step(sl.value, wl.value, s.ddx, w.ddx);
        dtdx = step(tl.value, wl.value, tt.ddx, w.ddx);
        dsdy = step(sb.value, wb.value, s.ddy, w.ddy);
        dtdy = step(tb.value, wb.value, tt.ddy, w.ddy);
        if (!f.s.finite() || !f.t.finite() || !dsdx.finite() || !dtdx.finite() || !dsdy.finite() ||
            !dtdy.finite())
          f.everything = true;
      }
    }
    if (f.everything) {
      f.s = f.t = {0, 1};
      f.lod = {0, static_cast<double>(shading_.finestLevel)};
      return f;
    }
    f.s = clamp(f.s, 0, 1);
    f.t = clamp(f.t, 0, 1);
    f.lod = lodRange(dsdx, dtdx, dsdy, dtdy);
    return f;
  }

  // The needed level's bounds and the colour bounds of candidate t.
  Alternative alternative(const SetupTriangle& t, int32_t index, const FragmentRange& f,
                          const OracleFragment& oracle) {
    Alternative a;
    a.triangle = static_cast<int32_t>(t.primitive);
    const int L = shading_.finestLevel;
    a.levelLo = static_cast<uint8_t>(std::clamp(static_cast<int>(std::ceil(f.lod.lo)), 0, L));
    a.levelHi = static_cast<uint8_t>(std::clamp(static_cast<int>(std::ceil(f.lod.hi)), 0, L));
    setUv(f.s, f.t, a);
    const Colour colour = shade(f.s, f.t, f.lod);
    store(colour, a.colorLo, a.colorHi);
    if (index == oracle.index) {
      // The filter's and the conversion's share alone: from the oracle's (s, t) and LOD.
      // (s, t) as the shader samples them: clamped to [0, 1] like f.s and f.t above (the
      // oracle's own are the interpolated values, past 1 on a quad whose coordinates run past).
      const Colour narrow =
          shade(clamp(Interval::point(oracle.uv.x), 0, 1),
                clamp(Interval::point(oracle.uv.y), 0, 1), Interval::point(oracle.lod));
      store(narrow, a.filterLo, a.filterHi);
      // The oracle's own value is in both (its arithmetic is one the model allows).
      a.filterLo = glm::min(a.filterLo, oracle.color);
      a.filterHi = glm::max(a.filterHi, oracle.color);
      a.colorLo = glm::min(a.colorLo, a.filterLo);
      a.colorHi = glm::max(a.colorHi, a.filterHi);
      a.levelLo = static_cast<uint8_t>(std::min<int>(a.levelLo, oracle.neededLevel));
      a.levelHi = static_cast<uint8_t>(std::max<int>(a.levelHi, oracle.neededLevel));
      a.uvLo = glm::min(a.uvLo, oracle.uv);
      a.uvHi = glm::max(a.uvHi, oracle.uv);
    } else {
      a.filterLo = a.colorLo;
      a.filterHi = a.colorHi;
    }
    return a;
  }

 private:
  // (s, t) bounds into an alternative, rounded outwards to floats so that they still hold.
  static void setUv(Interval s, Interval t, Alternative& a) {
    a.uvLo = glm::vec2(static_cast<float>(s.lo), static_cast<float>(t.lo));
    a.uvHi = glm::vec2(static_cast<float>(s.hi), static_cast<float>(t.hi));
    a.uvLo = glm::vec2(std::nextafter(a.uvLo.x, -1.0f), std::nextafter(a.uvLo.y, -1.0f));
    a.uvHi = glm::vec2(std::nextafter(a.uvHi.x, 2.0f), std::nextafter(a.uvHi.y, 2.0f));
  }

  // A fine derivative's width at one step of attribute k along `axis` from its first centre
  // (cx, cy), whose source box reaches rho: PerturbedTriangle::ratioStepReach plus the float
  // error of a difference (floatStep) and the rounding of the middle's derivative in double.
  static double stepWidth(const OwnBlock& b, const PerturbedTriangle& moves, size_t k, int axis,
                          double cx, double cy, double rho) {
    const PerturbedTriangle::StepReach r = moves.ratioStepReach(b.n[k], axis, cx, cy, rho);
    const double size = 2 * (b.scale[k] + r.slope) + r.slope;
    return r.width + (b.relative + kFloatUlp) * size + b.rounding[k];
  }

  // OwnBlock's widths for candidate `index` over the block from (bx, by); not bounded where the
  // triangle is too small for first-order bounds, 1/w may vanish near the block, the texture is
  // sampled without trilinear blending (the level's choice jumps) or the decoding is free.
  void makeOwnBlock(int32_t index, const Snapped& snapped, int bx, int by, OwnBlock& b) const {
    constexpr int kBlock = Visibility::kBlock;
    b.index = index;
    b.bounded = false;
    b.levels.assign(static_cast<size_t>(shading_.finestLevel) + 1, LevelBounds{});
    b.texels.clear();
    const PerturbedTriangle& p = snapped.perturbed;
    if (!p.bounded() || !shading_.trilinear ||
        (shading_.blockCompressed && !model_.decodingPinned) ||
        shading_.finestLevel > static_cast<int>(kMaxLevel))
      return;
    const double x0 = bx + 0.5, y0 = by + 0.5, x1 = bx + kBlock - 0.5, y1 = by + kBlock - 0.5;
    const WindowBox box = p.sourceBoxOver(x0, y0, x1, y1);
    const double rho = std::max({x0 - box.x.lo, box.x.hi - x1, y0 - box.y.lo, box.y.hi - y1});
    const std::array<double, 2> e = {p.stepRadius(0), p.stepRadius(1)};
    const WindowBox around = perturbed_detail::grown(box, std::max(e[0], e[1]));
    const double relative = model_.attributeUlps * kFloatUlp;
    const std::array<Interval, 2> reach = p.ratios(snapped.s, snapped.t, box);
    b.w = p.oneOverW();
    b.n = {snapped.s, snapped.t};
    const AffinePlane& w = b.w;
    for (size_t k = 0; k < 2; ++k) {
      const AffinePlane& n = b.n[k];
      const PerturbedTriangle::RatioOver r = p.ratioOver(n, around, x0, y0, x1, y1);
      if (!r.finite || !reach[k].finite()) return;
      const double scale = std::max(r.scale, r.magnitude);
      const double g = r.gradient[0] + r.gradient[1];
      // fragment()'s float error of the value, and the rounding of the nominal value in double.
      b.floatError[k] = relative * scale + kFloatUlp + 0x1p-40 * scale;
      b.value[k] = g * rho + b.floatError[k];
      b.ax[k] = n.ax * w.a0 - n.a0 * w.ax;
      b.ay[k] = n.ay * w.a0 - n.a0 * w.ay;
      b.cross[k] = n.ax * w.ay - n.ay * w.ax;
      // The derivative at a step's middle in double: a few roundings of its terms, over (1/w)^2;
      // 2^-40 of the terms covers them.
      const double terms = std::fabs(n.ax * w.a0) + std::fabs(n.a0 * w.ax) +
                           std::fabs(n.ay * w.a0) + std::fabs(n.a0 * w.ay) +
                           std::fabs(b.cross[k]) * (around.x.magnitude() + around.y.magnitude());
      b.rounding[k] = 0x1p-40 * terms * r.inverseW2;
      b.scale[k] = scale;
    }
    b.sReach = clamp(widen(reach[0], 0, b.value[0]), 0, 1);
    b.tReach = clamp(widen(reach[1], 0, b.value[1]), 0, 1);
    b.valueError = samplerErrors(0).value;
    b.rho = rho;
    b.relative = relative;
    double sum = 0;
    for (size_t k = 0; k < 2; ++k) sum += b.value[k] + b.rounding[k];
    b.bounded = std::isfinite(sum);
  }

  // Level m's bounds over an OwnBlock's reach, made on first use.
  const LevelBounds& levelBounds(OwnBlock& b, int m) {
    LevelBounds& l = b.levels[static_cast<size_t>(m)];
    if (l.state != 0) return l;
    l.state = -1;
    const int last = (1 << m) - 1;
    const double scale = powerOfTwo(m);
    const glm::ivec2 page(floorToInt(b.sReach.lo * scale, last),
                          floorToInt(b.tReach.lo * scale, last));
    if (page.x != floorToInt(b.sReach.hi * scale, last) ||
        page.y != floorToInt(b.tReach.hi * scale, last))
      return l;
    const PageMap map = pageMap(page, m);
    Interval x = map.x(b.sReach), y = map.y(b.tReach);
    const SamplerErrors errors = samplerErrors(std::max(x.magnitude(), y.magnitude()));
    x = widen(x, 0, errors.position);
    y = widen(y, 0, errors.position);
    // The texels a bilinear sample at a position in the box reads.
    const glm::ivec2 origin(static_cast<int>(std::floor(x.lo - 0.5)),
                            static_cast<int>(std::floor(y.lo - 0.5)));
    const int width = static_cast<int>(std::floor(x.hi - 0.5)) + 2 - origin.x;
    const int height = static_cast<int>(std::floor(y.hi - 0.5)) + 2 - origin.y;
    // A block's reach is a few texels a side on the levels its LOD blends (about a texel per pixel
    // on the finer one); wider, at a level the LOD range reaches on a horizon, the pixel-by-pixel
    // bounds read fewer texels than the block would keep.
    constexpr int kMaxSide = 24;
    if (width > kMaxSide || height > kMaxSide) return l;
    const size_t offset = b.texels.size();
    b.texels.resize(offset + static_cast<size_t>(width * height));
    for (int ty = 0; ty < height; ++ty)
      for (int tx = 0; tx < width; ++tx)
        b.texels[offset + static_cast<size_t>(ty * width + tx)] =
            source_.texel(origin + glm::ivec2(tx, ty));
    l = {1, map, errors.position, origin, width, height, offset};
    return l;
  }

  // The bilinear filter at texel position (x, y) (texel centres at + 0.5) from a level's kept
  // texels, which hold the cell of (x, y).
  static glm::dvec4 keptBilinear(const OwnBlock& b, const LevelBounds& l, double x, double y) {
    const double fx0 = std::floor(x - 0.5), fy0 = std::floor(y - 0.5);
    const int ix = static_cast<int>(fx0) - l.origin.x, iy = static_cast<int>(fy0) - l.origin.y;
    const auto texel = [&](int dx, int dy) {
      return glm::dvec4(b.texels[l.offset + static_cast<size_t>((iy + dy) * l.width + ix + dx)]);
    };
    const double fx = x - 0.5 - fx0, fy = y - 0.5 - fy0;
    const glm::dvec4 row0 = texel(0, 0) + (texel(1, 0) - texel(0, 0)) * fx;
    const glm::dvec4 row1 = texel(0, 1) + (texel(1, 1) - texel(0, 1)) * fx;
    return row0 + (row1 - row0) * fy;
  }

  // The filter over a box of texel positions on a level kept by an OwnBlock, and at a point
  // `at` inside it; false where the box reads texels not kept. Its range: inside one cell between
  // texel centres the filter is bilinear, its bounds at the box's corners; across cells, its value
  // at the point within the Lipschitz bound, and within the texels' hull.
  bool localFilter(const OwnBlock& b, const LevelBounds& l, const WindowBox& box, glm::dvec2 at,
                   LocalFilter& f) const {
    const int x0 = static_cast<int>(std::floor(box.x.lo - 0.5)) - l.origin.x;
    const int y0 = static_cast<int>(std::floor(box.y.lo - 0.5)) - l.origin.y;
    const int x1 = static_cast<int>(std::floor(box.x.hi - 0.5)) + 1 - l.origin.x;
    const int y1 = static_cast<int>(std::floor(box.y.hi - 0.5)) + 1 - l.origin.y;
    if (!(x0 >= 0 && y0 >= 0 && x1 < l.width && y1 < l.height)) return false;
    const auto texel = [&](int tx, int ty) {
      return glm::ivec4(b.texels[l.offset + static_cast<size_t>(ty * l.width + tx)]);
    };
    glm::ivec4 lo(255), hi(0), dx(0), dy(0);
    for (int ty = y0; ty <= y1; ++ty)
      for (int tx = x0; tx <= x1; ++tx) {
        const glm::ivec4 v = texel(tx, ty);
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
        if (tx > x0) dx = glm::max(dx, glm::abs(v - texel(tx - 1, ty)));
        if (ty > y0) dy = glm::max(dy, glm::abs(v - texel(tx, ty - 1)));
        if (cornerStep_ != 0 && tx > x0 && ty > y0)
          f.rounding =
              glm::max(f.rounding, cornerRounding(glm::dvec4(texel(tx - 1, ty - 1)),
                                                  glm::dvec4(texel(tx, ty - 1)),
                                                  glm::dvec4(texel(tx - 1, ty)), glm::dvec4(v)));
      }
    f.lipschitzX = glm::dvec4(dx);
    f.lipschitzY = glm::dvec4(dy);
    if (x1 == x0 + 1 && y1 == y0 + 1) {
      // One cell: its four texels, the rows' values at the box's ends and at the point, then the
      // columns'.
      const glm::dvec4 c00(texel(x0, y0)), c10(texel(x1, y0)), c01(texel(x0, y1)),
          c11(texel(x1, y1));
      const glm::dvec4 d0 = c10 - c00, d1 = c11 - c01;
      const double cx = l.origin.x + x0 + 0.5, cy = l.origin.y + y0 + 0.5;  // the cell's corner
      const double fx[3] = {box.x.lo - cx, box.x.hi - cx, at.x - cx};
      const double fy[3] = {box.y.lo - cy, box.y.hi - cy, at.y - cy};
      f.range = nothing();
      for (size_t i = 0; i < 3; ++i) {
        const glm::dvec4 row0 = c00 + d0 * fx[i], row1 = c01 + d1 * fx[i];
        if (i == 2) {
          f.at = row0 + (row1 - row0) * fy[2];
          break;
        }
        for (size_t j = 0; j < 2; ++j) {
          const glm::dvec4 v = row0 + (row1 - row0) * fy[j];
          f.range.lo = glm::min(f.range.lo, v);
          f.range.hi = glm::max(f.range.hi, v);
        }
      }
      return true;
    }
    f.at = keptBilinear(b, l, at.x, at.y);
    // A few cells: on each the filter is bilinear, so its bounds lie at the box's corners and
    // where the box meets the lines through texel centres (stops, per axis); bilinearRange alike.
    constexpr size_t kMaxStops = 4;
    Stops<kMaxStops> xs, ys;
    if (xs.of(box.x) && ys.of(box.y)) {
      // Per x stop each texel row's value along x, then per y stop the lerp between two rows.
      f.range = nothing();
      std::array<glm::dvec4, kMaxStops + 1> rows;
      for (size_t i = 0; i < xs.count; ++i) {
        const double tx = xs.at[i] - 0.5;
        const int cx = std::min(static_cast<int>(std::floor(tx)) - l.origin.x, x1 - 1);
        const double fx = tx - (cx + l.origin.x);
        for (int r = y0; r <= y1; ++r) {
          const glm::dvec4 t0(texel(cx, r));
          rows[static_cast<size_t>(r - y0)] = t0 + (glm::dvec4(texel(cx + 1, r)) - t0) * fx;
        }
        for (size_t j = 0; j < ys.count; ++j) {
          const double ty = ys.at[j] - 0.5;
          const int cy = std::min(static_cast<int>(std::floor(ty)) - l.origin.y, y1 - 1);
          const double fy = ty - (cy + l.origin.y);
          const glm::dvec4& r0 = rows[static_cast<size_t>(cy - y0)];
          const glm::dvec4 v = r0 + (rows[static_cast<size_t>(cy - y0 + 1)] - r0) * fy;
          f.range.lo = glm::min(f.range.lo, v);
          f.range.hi = glm::max(f.range.hi, v);
        }
      }
      return true;
    }
    const glm::dvec4 change = f.lipschitzX * std::max(at.x - box.x.lo, box.x.hi - at.x) +
                              f.lipschitzY * std::max(at.y - box.y.lo, box.y.hi - at.y);
    f.range = {glm::max(glm::dvec4(lo), f.at - change), glm::min(glm::dvec4(hi), f.at + change)};
    return true;
  }

  bool depthPinned() const {
    return model_.coveragePinned() && model_.depthUlps == 0 && model_.depthRoundsToNearest;
  }
  // A window depth as the depth buffer stores it: a 24-bit one rounds (to nearest or either way).
  Interval depthStored(Interval z, DepthFormat format) const {
    if (format == DepthFormat::kDepth24)
      z = widen(z, 0, (model_.depthRoundsToNearest ? 0.5 : 1.0) / 16777215.0);
    return clamp(z, 0, 1);
  }

  // How far the model lets a vertex lie from its float window position: its snapping.
  double snapRadius() const { return std::ldexp(1.0, -model_.subpixelBits); }

  Interval lodRange(Interval dsdx, Interval dtdx, Interval dsdy, Interval dtdy) const {
    // e_max^2 = max(|dUV/dx|^2, |dUV/dy|^2): three correctly rounded operations per term and the
    // model's arithmetic error (GLSL 4.50: + - * correctly rounded).
    const double ops = (3 * kRounding + 3 * model_.arithmeticUlps * kFloatUlp);
    const Interval ex = widen(square(dsdx) + square(dtdx), ops);
    const Interval ey = widen(square(dsdy) + square(dtdy), ops);
    Interval e = widen(sqrt(max(ex, ey)), kRounding + model_.sqrtUlps * kFloatUlp);
    e = e * finestSide_;  // a power of two: exact
    const double L = shading_.finestLevel;
    // log2 of zero (all four derivatives zero) is undefined (GLSL 4.50, section 8.2): any level.
    if (!(e.lo > 0) || !e.finite()) return {0, L};
    Interval d = log2(e);
    // The interval's log2 is double precision; the model's lies within the GLSL table or within
    // the model's own wider bound.
    d = widen(d, std::max(model_.log2Ulps, kGlslLog2Ulps) * kFloatUlp,
              std::max(model_.log2AbsoluteError, kGlslLog2AbsoluteError));
    const Interval clamped = clamp(d, 0, L);
    return widen(Interval{L - clamped.hi, L - clamped.lo}, 0, L * kRounding);
  }

  // The colour of every (s, t) in the box and LOD in the interval, in units of 1/255.
  Colour shade(Interval s, Interval t, Interval lod) {
    const int L = shading_.finestLevel;
    const double tiny = kBlendRounding;
    if (!shading_.trilinear) {
      Colour c = nothing();
      for (int m = std::clamp(static_cast<int>(std::ceil(lod.lo)), 0, L);
           m <= std::clamp(static_cast<int>(std::ceil(lod.hi)), 0, L); ++m)
        c = hull(c, sampleLevel(s, t, m));
      return c;
    }
    Colour c = nothing();
    const int first = std::clamp(static_cast<int>(std::floor(lod.lo)), 0, L);
    const int last = std::clamp(static_cast<int>(std::floor(lod.hi)), 0, L);
    // Each level sampled once: a blend's finer level is the next blend's coarser one.
    Colour atCoarse = sampleLevel(s, t, first);
    for (int coarse = first; coarse <= last; ++coarse) {
      const Colour c0 = atCoarse;
      if (coarse == L) {
        c = hull(c, c0);
        continue;
      }
      const Colour c1 = atCoarse = sampleLevel(s, t, coarse + 1);
      c = hull(c, blend(c0, c1, clamp(Interval{lod.lo - coarse, lod.hi - coarse}, 0, 1)));
    }
    return widen(c, tiny);
  }

  // Bilinear lookups of level m over the (s, t) box: every page of level m the box touches, each
  // through its indirection entry (the page or its resident ancestor).
  Colour sampleLevel(Interval s, Interval t, int m) {
    const int last = (1 << m) - 1;
    const double scale = powerOfTwo(m);
    const int x0 = floorToInt(s.lo * scale, last), x1 = floorToInt(s.hi * scale, last);
    const int y0 = floorToInt(t.lo * scale, last), y1 = floorToInt(t.hi * scale, last);
    if (x1 - x0 > 3 || y1 - y0 > 3) return everyValue();
    const double step = 1 / scale;  // exact: a page's side in (s, t)
    Colour c = nothing();
    bool any = false;
    for (int py = y0; py <= y1; ++py)
      for (int px = x0; px <= x1; ++px) {
        const Interval ps{std::max(s.lo, px * step),
                          std::min(s.hi, px == last ? 1.0 : (px + 1) * step)};
        const Interval pt{std::max(t.lo, py * step),
                          std::min(t.hi, py == last ? 1.0 : (py + 1) * step)};
        // A box reaching no texel of this page (s or t outside [0, 1]) adds nothing.
        if (!(ps.lo <= ps.hi) || !(pt.lo <= pt.hi)) continue;
        const Colour page = samplePage(ps, pt, glm::ivec2(px, py), m);
        c = any ? hull(c, page) : page;  // (finite bounds: the first hull would return them)
        any = true;
      }
    return c;
  }

  Colour samplePage(Interval s, Interval t, glm::ivec2 page, int m) {
    const PageMap map = pageMap(page, m);
    Interval x = map.x(s), y = map.y(t);
    const SamplerErrors errors = samplerErrors(std::max(x.magnitude(), y.magnitude()));
    x = widen(x, 0, errors.position);
    y = widen(y, 0, errors.position);
    return widen(bilinearRange(x, y), errors.value);
  }

  // Page `page` of level m's PageMap, from its indirection entry.
  PageMap pageMap(glm::ivec2 page, int m) {
    const glm::uvec4 e = source_.entry(page, m);
    const int i = static_cast<int>(e.z);
    const int stored = shading_.pageSize + 2 * shading_.border;
    return {{static_cast<double>(e.x) * stored + shading_.border,
             static_cast<double>(e.y) * stored + shading_.border},
            {page.x >> (m - i), page.y >> (m - i)},
            powerOfTwo(i),
            shading_.pageSize};
  }

  // The corner-weight sampler (Filter::kFixedPointCorners) on a cell of texels c00, c10, c01, c11:
  // its sum differs from the exact bilinear filter at its rounded position only by the rounding of
  // w11 (half a step of 2^-weightBits, or a whole one floored) times c00 - c10 - c01 + c11, since
  // w10, w01 and w00 follow from w11. Callers ask only when cornerStep_ is not 0 (the other
  // members' errors are samplerErrors').
  glm::dvec4 cornerRounding(const glm::dvec4& c00, const glm::dvec4& c10, const glm::dvec4& c01,
                            const glm::dvec4& c11) const {
    return glm::abs(c00 - c10 - c01 + c11) * cornerStep_;
  }
  // The same bound over every texel value the filter could read (|cross term| <= 2 * 255).
  double worstCornerRounding() const { return 510 * cornerStep_; }

  // How far a bilinear sample's texel position (in cache texels, at most `magnitude`) and its
  // value (units of 1/255) may lie from the exact filter's at the exact position, under the model.
  struct SamplerErrors {
    double position, value;
  };
  SamplerErrors samplerErrors(double magnitude) const {
    // The shader's float arithmetic for the texel position: a product and two sums of values up
    // to the cache's size.
    SamplerErrors e{4 * kFloatUlp * magnitude, 16 * kFloatUlp * 255};
    if (!shading_.exactFilter) {
      // The sampler: the position is divided by the cache size and multiplied back (two more
      // roundings), then quantised to its sub-texel grid; the lerps round as the model says.
      e.position *= 2;
      if (!model_.filterPinned) {
        e.position += subTexelStep_;
        e.value = model_.filterErrorUnits;
      } else if (const Filter& f = model_.arithmetic.filter;
                 f.weights == FilterWeights::kFixedPointCorners) {
        // The coordinate truncated to 2^-coordinateBits of the cache's side, the position rounded
        // to 2^-weightBits texel (half a step either way, or a whole one down); the corner
        // product's rounding is the cell's (cornerRounding), the result's rounding here.
        const double step = std::ldexp(1.0, -f.weightBits);
        e.position += shading_.cacheSide * std::ldexp(1.0, -f.coordinateBits) +
                      (f.positionRounding == PositionRounding::kHalfUp ? step / 2 : step);
        e.value += f.output == FilterOutput::kUnorm8    ? 0.5
                   : f.output == FilterOutput::kUnorm16 ? 0.5 * 255 / 65535
                                                        : 0.0;
      } else if (model_.arithmetic.filter.weights == FilterWeights::kFixedPoint8) {
        e.position += kFixedPointSubTexelStep;
        // Three lerps, each rounded to nearest: 0.5 + 0.5; each floored: under 1 + 1.
        e.value = model_.arithmetic.filter.lerpRounding == LerpRounding::kNearest ? 1.0 : 2.0;
      }
    } else {
      e.value += model_.arithmeticUlps * kFloatUlp * 255 * 4;
    }
    return e;
  }

  // Bounds of the bilinear filter (texel centres at +0.5, clamped fetches) over a box of texel
  // positions: on each cell between texel centres the filter is bilinear, so its bounds lie at
  // the box's corners and where the box meets the lines through texel centres.
  Colour bilinearRange(Interval x, Interval y) {
    // Per axis the stops: the box's ends and the texel centres strictly inside.
    constexpr size_t kMaxPoints = 64;
    // Beyond 16 texels a wide box is bounded by the whole range (below); one this wide has more
    // stops than fit, so it is wide whatever the other axis.
    constexpr double kSurelyWide = kMaxPoints + 2;
    if (x.width() >= kSurelyWide || y.width() >= kSurelyWide) return everyValue();
    if (model_.decodingPinned || !shading_.blockCompressed) {
      // The common box: inside one cell between texel centres on both axes (a box narrower than a
      // texel mostly is), where the stops are its ends alone.
      const double cx0 = std::floor(x.lo - 0.5), cy0 = std::floor(y.lo - 0.5);
      if (cx0 == std::floor(x.hi - 0.5) && cy0 == std::floor(y.hi - 0.5))
        return bilinearInCell(x, y, cx0, cy0);
    }
    Stops<kMaxPoints + 2> xs, ys;
    // Each texel as the least and greatest value it may have: one value unless the block
    // decoding is free. Channels as doubles (exact): the least values of the four channels, then
    // the greatest.
    using Range = std::array<double, 8>;
    const auto fetch = [&](glm::ivec2 at, Range& r) {
      std::array<glm::u8vec4, 2> v;
      if (!model_.decodingPinned && shading_.blockCompressed) {
        v = source_.texelRange(at);
      } else {
        v[0] = v[1] = source_.texel(at);
      }
      for (int k = 0; k < 4; ++k) {
        r[static_cast<size_t>(k)] = v[0][k];
        r[static_cast<size_t>(k) + 4] = v[1][k];
      }
    };
    // The least of the low values and the greatest of the high ones met so far.
    Range bounds;
    for (size_t k = 0; k < 4; ++k) {
      bounds[k] = std::numeric_limits<double>::infinity();
      bounds[k + 4] = -std::numeric_limits<double>::infinity();
    }
    const auto include = [&bounds](const Range& v) {
      for (size_t k = 0; k < 4; ++k) bounds[k] = std::min(bounds[k], v[k]);
      for (size_t k = 4; k < 8; ++k) bounds[k] = std::max(bounds[k], v[k]);
    };
    const auto colour = [&bounds] {
      return Colour{{bounds[0], bounds[1], bounds[2], bounds[3]},
                    {bounds[4], bounds[5], bounds[6], bounds[7]}};
    };
    if (!xs.of(x) || !ys.of(y) || xs.count * ys.count > kMaxPoints) {
      // A wide box: every texel it reaches bounds the filter (a convex combination of them);
      // beyond 16 x 16 texels, the whole range (cheaper than reading them, and still a bound).
      if (y.width() > 16 || x.width() > 16) return everyValue();
      for (int ty = static_cast<int>(std::floor(y.lo - 0.5));
           ty <= static_cast<int>(std::floor(y.hi - 0.5)) + 1; ++ty)
        for (int tx = static_cast<int>(std::floor(x.lo - 0.5));
             tx <= static_cast<int>(std::floor(x.hi - 0.5)) + 1; ++tx) {
          Range v;
          fetch({tx, ty}, v);
          include(v);
        }
      return colour();
    }
    // The texels the stops read, each fetched once: a box spans at most one cell more than it
    // has stops per axis, so (xs + 1) (ys + 1) <= 99 texels with xs ys <= 64 and both at least 2.
    const glm::ivec2 origin(static_cast<int>(std::floor(x.lo - 0.5)),
                            static_cast<int>(std::floor(y.lo - 0.5)));
    const int width = static_cast<int>(std::floor(x.hi - 0.5)) + 2 - origin.x;
    const int height = static_cast<int>(std::floor(y.hi - 0.5)) + 2 - origin.y;
    constexpr int kMaxTexels = 128;
    if (width * height > kMaxTexels)  // never (see above); a bound all the same
      return everyValue();
    std::array<Range, kMaxTexels> block;
    for (int ty = 0; ty < height; ++ty)
      for (int tx = 0; tx < width; ++tx)
        fetch(origin + glm::ivec2(tx, ty), block[static_cast<size_t>(ty * width + tx)]);
    // Texels that are one value (no free block decoding) need the least bounds only: the greatest
    // are the same operations on the same values.
    const size_t channels = !model_.decodingPinned && shading_.blockCompressed ? 8 : 4;
    // Per x stop, each texel row's value along x; then per y stop the lerp between two rows. The
    // filter's weights are not negative: it grows with every texel, so its least value comes from
    // the least texels and its greatest from the greatest.
    std::array<Range, kMaxTexels> rows;
    for (size_t i = 0; i < xs.count; ++i) {
      const double tx = xs.at[i] - 0.5;
      const double bx = std::floor(tx), fx = tx - bx;
      const int column = static_cast<int>(bx) - origin.x;
      for (int ty = 0; ty < height; ++ty) {
        const Range& c0 = block[static_cast<size_t>(ty * width + column)];
        const Range& c1 = block[static_cast<size_t>(ty * width + column + 1)];
        Range& row = rows[static_cast<size_t>(ty)];
        for (size_t k = 0; k < channels; ++k) row[k] = c0[k] + (c1[k] - c0[k]) * fx;
      }
      for (size_t j = 0; j < ys.count; ++j) {
        const double ty = ys.at[j] - 0.5;
        const double by = std::floor(ty), fy = ty - by;
        const Range& row0 = rows[static_cast<size_t>(static_cast<int>(by) - origin.y)];
        const Range& row1 = rows[static_cast<size_t>(static_cast<int>(by) - origin.y + 1)];
        Range value;
        for (size_t k = 0; k < channels; ++k) value[k] = row0[k] + (row1[k] - row0[k]) * fy;
        if (channels == 4)
          for (size_t k = 0; k < 4; ++k) value[k + 4] = value[k];
        include(value);
      }
    }
    if (cornerStep_ == 0) return colour();
    // The corner rounding of any cell the box reads: its texels' own, or with free decoding
    // the bound over any values.
    glm::dvec4 rounding(channels == 8 ? worstCornerRounding() : 0.0);
    if (channels == 4)
      for (int ty = 0; ty + 1 < height; ++ty)
        for (int tx = 0; tx + 1 < width; ++tx) {
          const auto at = [&](int dx, int dy) {
            const Range& r = block[static_cast<size_t>((ty + dy) * width + tx + dx)];
            return glm::dvec4(r[0], r[1], r[2], r[3]);
          };
          rounding = glm::max(rounding, cornerRounding(at(0, 0), at(1, 0), at(0, 1), at(1, 1)));
        }
    const Colour c = colour();
    return {c.lo - rounding, c.hi + rounding};
  }

  // bilinearRange for a box inside the cell whose lower-left texel is (cx0, cy0), texels of one
  // value: the same operations as the general case on its four texels, at the box's corners.
  Colour bilinearInCell(Interval x, Interval y, double cx0, double cy0) {
    const glm::ivec2 origin(static_cast<int>(cx0), static_cast<int>(cy0));
    // The two last cells read are kept: a pixel's box and its oracle's point mostly share the
    // cells of the two levels they blend.
    Cell* cell = &cells_[0];
    if (cells_[1].origin == origin) {
      cell = &cells_[1];
    } else if (cells_[0].origin != origin) {
      cell = &cells_[nextCell_];
      nextCell_ ^= 1;
      cell->origin = origin;
      cell->texels = {glm::dvec4(source_.texel(origin)),
                      glm::dvec4(source_.texel(origin + glm::ivec2(1, 0))),
                      glm::dvec4(source_.texel(origin + glm::ivec2(0, 1))),
                      glm::dvec4(source_.texel(origin + glm::ivec2(1, 1)))};
    }
    const glm::dvec4 &c00 = cell->texels[0], &c10 = cell->texels[1], &c01 = cell->texels[2],
                     &c11 = cell->texels[3];
    const double fx[2] = {(x.lo - 0.5) - cx0, (x.hi - 0.5) - cx0};
    const double fy[2] = {(y.lo - 0.5) - cy0, (y.hi - 0.5) - cy0};
    Colour c = nothing();
    for (double wx : fx) {
      const glm::dvec4 row0 = c00 + (c10 - c00) * wx, row1 = c01 + (c11 - c01) * wx;
      for (double wy : fy) {
        const glm::dvec4 v = row0 + (row1 - row0) * wy;
        c.lo = glm::min(c.lo, v);
        c.hi = glm::max(c.hi, v);
      }
    }
    if (cornerStep_ != 0) {
      const glm::dvec4 rounding = cornerRounding(c00, c10, c01, c11);
      c = {c.lo - rounding, c.hi + rounding};
    }
    return c;
  }

  // Float colour bounds (units of 1/255) to 8-bit bounds under the model's conversion.
  void store(const Colour& c, glm::u8vec4& lo, glm::u8vec4& hi) const {
    // The float colour (value x 255 in [0, 255]) carries the rounding of its last few float
    // operations, 16 units of 2^-23 of 255 as valueError counts them: below 2^-11.
    constexpr double kSlack = 16 * kFloatUlp * 255;
    for (int k = 0; k < 4; ++k) {
      const Interval v = clamp(Interval{c.lo[k], c.hi[k]}, 0, 255);
      double l, h;
      const ColourConversion& conversion = model_.arithmetic.colourConversion;
      if (model_.colorPinned && conversion.rule == ColourConversionRule::kQuantized) {
        // It does not decrease with the value: its values at the interval's ends.
        l = quantizedUnorm8(std::clamp((v.lo - kSlack) / 255, 0.0, 1.0), conversion);
        h = quantizedUnorm8(std::clamp((v.hi + kSlack) / 255, 0.0, 1.0), conversion);
      } else if (model_.colorPinned) {
        l = std::ceil(v.lo - 0.5 - kSlack);
        h = std::floor(v.hi + 0.5 + kSlack);
      } else {
        l = std::floor(v.lo - kSlack);
        h = std::ceil(v.hi + kSlack);
      }
      lo[k] = static_cast<uint8_t>(std::clamp(l, 0.0, 255.0));
      hi[k] = static_cast<uint8_t>(std::clamp(h, 0.0, 255.0));
    }
  }

  const PrecisionModel& model_;
  SetShading shading_;
  Viewport viewport_;
  TexelSource& source_;
  double finestSide_ = 1;
  double subTexelStep_ = 1;  // a free sampler's texel positions: 2^-subTexelBits texel
  double cornerStep_ = 0;    // the corner-weight sampler's w11 rounding (cornerRounding)
  std::unordered_map<int32_t, Snapped> snapped_;  // by set-up index (elements never move)
  // The four texels of the cells bilinearInCell read last (the cache does not change meanwhile).
  struct Cell {
    glm::ivec2 origin{std::numeric_limits<int>::min()};
    std::array<glm::dvec4, 4> texels;
  };
  std::array<Cell, 2> cells_;
  size_t nextCell_ = 0;
  struct BlockSlot {
    int x = -1, y = -1;
    std::vector<BlockClass> classes;
    std::vector<OwnBlock> own;  // the first ownCount are this block's (kept for their storage)
    size_t ownCount = 0;
  };
  static constexpr int kBlockSlots = Visibility::kTile / Visibility::kBlock;
  std::array<BlockSlot, kBlockSlots> blocks_;
};

// A candidate that may cover the pixel, with its depth there.
struct PixelCandidate {
  int32_t index;
  Snapped* snapped;  // when the model moves vertices
  PieceCoverage piece;
  Interval z;
  int cover;  // of the mesh triangle: the piece's, or 2 where its fan surely covers
};

// A fan piece whose centre is surely inside the mesh triangle's edges and may lie beyond edges it
// shares with neighbours surely covers the mesh triangle when each such neighbour is a candidate
// of the same kind: walking across the open edges from piece to piece ends in the piece that holds
// the centre (the fan turns one way around its first vertex), whatever the vertices' moves.
void surelyCoveredByTheirFans(const std::vector<SetupTriangle>& triangles,
                              std::vector<PixelCandidate>& list) {
  const auto fanOf = [&](const PixelCandidate& c) -> const SetupTriangle& {
    return triangles[static_cast<size_t>(c.index)];
  };
  // Whether the fan of set-up triangle `index` has a triangle at fanIndex `position`, or the fan
  // ends before it (then true: nothing to cross to). A fan's triangles are adjacent in the list.
  const auto setUp = [&](int32_t index, int64_t position) {
    const uint32_t primitive = triangles[static_cast<size_t>(index)].primitive;
    int64_t last = -1;
    for (int64_t j = index; j >= 0 && triangles[static_cast<size_t>(j)].primitive == primitive; --j)
      if (triangles[static_cast<size_t>(j)].fanIndex == position) return true;
    for (size_t j = static_cast<size_t>(index);
         j < triangles.size() && triangles[j].primitive == primitive; ++j) {
      if (triangles[j].fanIndex == position) return true;
      last = std::max<int64_t>(last, triangles[j].fanIndex);
    }
    return position > last;
  };
  const auto memberOf = [](const PieceCoverage& p) {
    return p.cover == 2 || (p.boundarySure && p.openFanEdges != 0);
  };
  if (std::none_of(list.begin(), list.end(), [&](const PixelCandidate& c) {
        return c.piece.cover == 1 && memberOf(c.piece);
      }))
    return;
  std::vector<char> member(list.size());
  for (size_t i = 0; i < list.size(); ++i) member[i] = memberOf(list[i].piece);
  // Drop members with an open edge whose neighbour is no member, until none is left to drop.
  for (bool dropped = true; dropped;) {
    dropped = false;
    for (size_t i = 0; i < list.size(); ++i) {
      if (!member[i] || list[i].piece.cover == 2) continue;
      const SetupTriangle& t = fanOf(list[i]);
      for (size_t e = 0; e < 3 && member[i]; ++e) {
        if (!(list[i].piece.openFanEdges & (1u << e))) continue;
        // The neighbour across the edge; a piece that set-up dropped (no area, or no pixel
        // centre) is crossed to the one after it.
        const int step = t.fanNeighbour[e];
        int64_t next = int64_t{t.fanIndex} + step;
        while (next >= 0 && !setUp(list[i].index, next)) next += step;
        bool found = false;
        for (size_t j = 0; j < list.size() && !found; ++j)
          found = member[j] && fanOf(list[j]).primitive == t.primitive &&
                  int64_t{fanOf(list[j]).fanIndex} == next;
        if (!found) {
          member[i] = 0;
          dropped = true;
        }
      }
    }
  }
  for (size_t i = 0; i < list.size(); ++i)
    if (member[i]) list[i].cover = 2;
}

}  // namespace

struct ResultSetBuilder::Impl {
  Impl(const PrecisionModel& model, const SetShading& shading,
       const std::vector<SetupTriangle>& triangles, Viewport viewport, DepthFormat depthFormat,
       TexelSource& source)
      : builder(model, shading, viewport, source), triangles(triangles), depthFormat(depthFormat) {}
  Builder builder;
  const std::vector<SetupTriangle>& triangles;
  DepthFormat depthFormat;
  std::vector<BlockClass> classes;   // of the current pixel's candidates
  std::vector<PixelCandidate> list;  // those that may cover it
};

ResultSetBuilder::ResultSetBuilder(const PrecisionModel& model, const SetShading& shading,
                                   const std::vector<SetupTriangle>& triangles, Viewport viewport,
                                   DepthFormat depthFormat, TexelSource& source)
    : impl_(std::make_unique<Impl>(model, shading, triangles, viewport, depthFormat, source)) {}

ResultSetBuilder::~ResultSetBuilder() = default;

void ResultSetBuilder::append(const Visibility::BlockCandidates& candidates, int px, int py,
                              const OracleFragment& oracle, std::vector<Alternative>& out) {
  Builder& builder = impl_->builder;
  const std::vector<SetupTriangle>& triangles = impl_->triangles;
  const DepthFormat depthFormat = impl_->depthFormat;
  // The candidates' classes over the pixel's block; those that surely cover no centre of it
  // drop out at once.
  std::vector<BlockClass>& classes = impl_->classes;
  classes.clear();
  double front = std::numeric_limits<double>::infinity();  // of those surely covering the block
  constexpr int kBlock = Visibility::kBlock;
  const int bx = px - px % kBlock, by = py - py % kBlock;
  const uint16_t bit = Visibility::BlockCandidates::bitOf(px - bx, py - by);
  std::vector<BlockClass>& known = builder.blockClasses(bx, by, candidates.triangles.size());
  for (size_t i = 0; i < candidates.triangles.size(); ++i) {
    if (!(candidates.pixels[i] & bit)) continue;
    const int32_t index = candidates.triangles[i];
    if (known[i].cover == -2)
      known[i] =
          builder.blockClass(triangles[static_cast<size_t>(index)], index, bx, by, depthFormat);
    const BlockClass& c = known[i];
    if (c.cover == 0) continue;
    classes.push_back(c);
    if (c.cover == 2 && c.z.hi < 1.0) front = std::min(front, c.z.hi);
  }
  // Behind a candidate that surely covers every centre of the block and is surely nearer
  // everywhere in it: at this pixel too it surely beats this one, and beats whatever this one
  // beats, so leaving it out changes nothing; unless it is the oracle's own, or a piece of a
  // clipped fan (the fan's union reads its pieces).
  const auto hidden = [&](const BlockClass& c) {
    const SetupTriangle& t = triangles[static_cast<size_t>(c.index)];
    const bool fanPiece =
        t.fanNeighbour[0] != 0 || t.fanNeighbour[1] != 0 || t.fanNeighbour[2] != 0;
    return front < c.z.lo && c.index != oracle.index && !fanPiece;
  };
  // A lone candidate is compared with the cleared depth alone: where it surely covers the block,
  // the block's depth bounds (which hold the pixel's) decide as well.
  const size_t shown = static_cast<size_t>(std::count_if(
      classes.begin(), classes.end(), [&](const BlockClass& c) { return !hidden(c); }));
  std::vector<PixelCandidate>& list = impl_->list;
  list.clear();
  for (const BlockClass& c : classes) {
    if (hidden(c)) continue;
    const int32_t index = c.index;
    const SetupTriangle& t = triangles[static_cast<size_t>(index)];
    Snapped* s = c.snapped ? c.snapped : builder.snapped(t, index);
    const PieceCoverage piece = c.cover == 2 ? PieceCoverage{2} : builder.coverage(t, s, px, py);
    if (piece.cover == 0) continue;
    const Interval z = shown == 1 && c.cover == 2 ? c.z : builder.depth(t, s, px, py, depthFormat);
    if (!(z.lo < 1.0)) continue;  // never passes GL_LESS against the cleared 1.0
    list.push_back({index, s, piece, z, piece.cover});
  }
  surelyCoveredByTheirFans(triangles, list);
  const auto surelyBeats = [](const PixelCandidate& d, const PixelCandidate& c) {
    if (d.cover != 2 || !(d.z.hi < 1.0)) return false;
    // Points: the pinned depth test, where the earlier drawn triangle wins a tie.
    if (d.z.lo == d.z.hi && c.z.lo == c.z.hi)
      return d.z.lo < c.z.lo || (d.z.lo == c.z.lo && d.index < c.index);
    return d.z.hi < c.z.lo;
  };
  bool mayBeEmpty = true;
  const PixelCandidate* own = nullptr;
  for (const PixelCandidate& c : list) {
    if (c.cover == 2 && c.z.hi < 1.0) mayBeEmpty = false;
    if (c.index == oracle.index) own = &c;
  }
  for (const PixelCandidate& c : list) {
    bool possible = true;
    for (const PixelCandidate& d : list)
      if (&d != &c && surelyBeats(d, c)) possible = false;
    if (!possible && c.index != oracle.index) continue;
    const SetupTriangle& t = triangles[static_cast<size_t>(c.index)];
    Alternative a;
    if (c.index != oracle.index || !c.snapped ||
        !builder.ownAlternative(t, c.index, *c.snapped, px, py, oracle, a))
      a = builder.alternative(t, c.index, builder.fragment(t, c.snapped, px, py), oracle);
    if (c.index != oracle.index)
      a.reasons = (c.cover == 2 && own && own->cover == 2) ? kReasonDepth : kReasonCoverage;
    out.push_back(a);
  }
  if (oracle.index >= 0 && !own) {
    // The oracle's own triangle, should the bounds above have missed it.
    const SetupTriangle& t = triangles[static_cast<size_t>(oracle.index)];
    out.push_back(builder.alternative(
        t, oracle.index, builder.fragment(t, builder.snapped(t, oracle.index), px, py), oracle));
  }
  if (mayBeEmpty || oracle.index < 0) {
    Alternative empty;
    empty.triangle = -1;
    empty.reasons = oracle.index < 0 ? 0 : kReasonCoverage;
    out.push_back(empty);
  }
}

}  // namespace vt::reference
