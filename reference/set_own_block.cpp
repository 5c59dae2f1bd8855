// The oracle's own triangle over a 4 x 4 block (set_builder.h, OwnBlock): the widths its pixels
// share, the texels each level's reach reads, and each pixel's alternative from them.

#include <algorithm>
#include <cmath>

#include "format/page_address.h"
#include "reference/set_builder.h"

namespace vt::reference::sets {

OwnBlock& Builder::ownBlock(int32_t index, const Snapped& snapped, int bx, int by) {
  constexpr int kBlock = Visibility::kBlock;
  BlockSlot& slot = blocks_[static_cast<size_t>((bx / kBlock) % kBlockSlots)];
  for (size_t k = 0; k < slot.ownCount; ++k)
    if (slot.own[k].index == index) return slot.own[k];
  if (slot.ownCount == slot.own.size()) slot.own.emplace_back();
  OwnBlock& b = slot.own[slot.ownCount++];
  makeOwnBlock(index, snapped, bx, by, b);
  return b;
}

bool Builder::ownAlternative(const SetupTriangle& t, int32_t index, const Snapped& snapped, int px,
                             int py, const OracleFragment& oracle, Alternative& a) {
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
    return std::min(b.rho, (moves.sourceBox(x, y).x.hi - x) * (1 + kDoubleSlack));
  };
  const double rho = reach(cx, cy), rhoLeft = reach(mx - 0.5, cy), rhoLower = reach(cx, my - 0.5);
  std::array<Interval, 4> d;    // ds/dx, dt/dx, ds/dy, dt/dy
  std::array<double, 2> value;  // how far a set's s and t lie from the nominal values
  for (size_t k = 0; k < 2; ++k) {
    const double slopeX = (b.ax[k] + b.cross[k] * cy) / wx2;
    const double slopeY = (b.ay[k] - b.cross[k] * cx) / wy2;
    d[k] = Interval::around(slopeX, stepWidth(b, moves, k, 0, mx - 0.5, cy, rhoLeft));
    d[k + 2] = Interval::around(slopeY, stepWidth(b, moves, k, 1, cx, my - 0.5, rhoLower));
    value[k] = std::min(b.value[k], moves.ratioReach(b.n[k], cx, cy, rho) + b.floatError[k]);
  }
  const Interval lod = hull(lodRange(d[0], d[1], d[2], d[3]), Interval::point(oracle.lod));
  // The set's (s, t), as the shader samples them: clamped to [0, 1].
  const Interval s =
      clamp(hull(Interval::around(sNominal, value[0]), Interval::point(oracle.uv.x)), 0, 1);
  const Interval tt =
      clamp(hull(Interval::around(tNominal, value[1]), Interval::point(oracle.uv.y)), 0, 1);
  OwnColour colour;
  if (!ownColour(b, s, tt, so, to, lod, oracle.lod, colour)) return false;
  const int L = shading_.finestLevel;
  a.triangle = static_cast<int32_t>(t.primitive);
  a.levelLo = static_cast<uint8_t>(
      std::min(std::clamp(static_cast<int>(std::ceil(lod.lo)), 0, L), oracle.neededLevel));
  a.levelHi = static_cast<uint8_t>(
      std::max(std::clamp(static_cast<int>(std::ceil(lod.hi)), 0, L), oracle.neededLevel));
  setUv(s, tt, a);
  a.uvLo = glm::min(a.uvLo, oracle.uv);
  a.uvHi = glm::max(a.uvHi, oracle.uv);
  store(colour.colour, a.colorLo, a.colorHi);
  store({colour.centre - colour.filter, colour.centre + colour.filter}, a.filterLo, a.filterHi);
  a.filterLo = glm::min(a.filterLo, oracle.color);
  a.filterHi = glm::max(a.filterHi, oracle.color);
  a.colorLo = glm::min(a.colorLo, a.filterLo);
  a.colorHi = glm::max(a.colorHi, a.filterHi);
  return true;
}

bool Builder::ownColour(OwnBlock& b, Interval s, Interval tt, double so, double to, Interval lod,
                        float oracleLodAsDrawn, OwnColour& out) {
  const int L = shading_.finestLevel;
  // The blends from level `first` to `top` (trilinear: each with the next finer level).
  const int first = std::clamp(static_cast<int>(std::floor(lod.lo)), 0, L);
  const int top = std::clamp(static_cast<int>(std::floor(lod.hi)), first, L);
  const int last = std::min(top + 1, L);
  // Per level the LOD reaches, the filter over every texel position a set admits (those of its
  // (s, t) box, within the sampler's position error); and over the oracle's position alone, as
  // the Lipschitz bound of the sampler's position error.
  std::array<Colour, kMaxLevel + 1> range;  // (finestLevel <= kMaxLevel: format/page_address.h)
  // The exact filter at the oracle's (s, t) on the two levels its LOD blends.
  const double oracleLod = std::clamp<double>(oracleLodAsDrawn, 0, L);
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
  out.colour = widen(colour, kBlendRounding);
  // The filter alone: the exact filter at the oracle's (s, t) and LOD, within the sampler's
  // position error's change, its value error and the blend's rounding.
  out.centre = oracleCoarse == L
                   ? atOracle[0]
                   : atOracle[0] + (atOracle[1] - atOracle[0]) * (oracleLod - oracleCoarse);
  out.filter = own + b.valueError + kBlendRounding;
  return true;
}

double Builder::stepWidth(const OwnBlock& b, const PerturbedTriangle& moves, size_t k, int axis,
                          double cx, double cy, double rho) {
  const PerturbedTriangle::StepReach r = moves.ratioStepReach(b.n[k], axis, cx, cy, rho);
  const double size = 2 * (b.scale[k] + r.slope) + r.slope;
  return r.width + (b.relative + kFloatUlp) * size + b.rounding[k];
}

void Builder::makeOwnBlock(int32_t index, const Snapped& snapped, int bx, int by,
                           OwnBlock& b) const {
  constexpr int kBlock = Visibility::kBlock;
  b.index = index;
  b.bounded = false;
  b.levels.assign(static_cast<size_t>(shading_.finestLevel) + 1, LevelBounds{});
  b.texels.clear();
  const PerturbedTriangle& p = snapped.perturbed;
  if (!p.bounded() || !shading_.trilinear || (shading_.blockCompressed && !model_.decodingPinned) ||
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
    b.floatError[k] = relative * scale + kFloatUlp + kDoubleSlack * scale;
    b.value[k] = g * rho + b.floatError[k];
    b.ax[k] = n.ax * w.a0 - n.a0 * w.ax;
    b.ay[k] = n.ay * w.a0 - n.a0 * w.ay;
    b.cross[k] = n.ax * w.ay - n.ay * w.ax;
    // The derivative at a step's middle in double: a few roundings of its terms, over (1/w)^2;
    // kDoubleSlack of the terms covers them.
    const double terms = std::fabs(n.ax * w.a0) + std::fabs(n.a0 * w.ax) + std::fabs(n.ay * w.a0) +
                         std::fabs(n.a0 * w.ay) +
                         std::fabs(b.cross[k]) * (around.x.magnitude() + around.y.magnitude());
    b.rounding[k] = kDoubleSlack * terms * r.inverseW2;
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

const LevelBounds& Builder::levelBounds(OwnBlock& b, int m) {
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

glm::dvec4 Builder::keptBilinear(const OwnBlock& b, const LevelBounds& l, double x, double y) {
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

bool Builder::localFilter(const OwnBlock& b, const LevelBounds& l, const WindowBox& box,
                          glm::dvec2 at, LocalFilter& f) const {
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
    const glm::dvec4 c00(texel(x0, y0)), c10(texel(x1, y0)), c01(texel(x0, y1)), c11(texel(x1, y1));
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

}  // namespace vt::reference::sets
