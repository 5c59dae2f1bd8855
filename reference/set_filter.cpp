// The colour of every (s, t) and LOD a candidate may have (set_builder.h): the levels the LOD
// blends, the pages each touches through the indirection table, the bilinear filter's bounds over
// a box of texel positions, and the 8-bit values the model's conversion may store.

#include <algorithm>
#include <cmath>

#include "reference/framebuffer_conversion.h"
#include "reference/set_builder.h"

namespace vt::reference::sets {

Colour Builder::shade(Interval s, Interval t, Interval lod) {
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

Colour Builder::sampleLevel(Interval s, Interval t, int m) {
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

Colour Builder::samplePage(Interval s, Interval t, glm::ivec2 page, int m) {
  const PageMap map = pageMap(page, m);
  Interval x = map.x(s), y = map.y(t);
  const SamplerErrors errors = samplerErrors(std::max(x.magnitude(), y.magnitude()));
  x = widen(x, 0, errors.position);
  y = widen(y, 0, errors.position);
  return widen(bilinearRange(x, y), errors.value);
}

PageMap Builder::pageMap(glm::ivec2 page, int m) {
  const glm::uvec4 e = source_.entry(page, m);
  const int i = static_cast<int>(e.z);
  const int stored = shading_.pageSize + 2 * shading_.border;
  return {{static_cast<double>(e.x) * stored + shading_.border,
           static_cast<double>(e.y) * stored + shading_.border},
          {page.x >> (m - i), page.y >> (m - i)},
          powerOfTwo(i),
          shading_.pageSize};
}

Builder::SamplerErrors Builder::samplerErrors(double magnitude) const {
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

Colour Builder::bilinearRange(Interval x, Interval y) {
  // Beyond 16 texels a wide box is bounded by the whole range (texelHull); one this wide has more
  // stops than fit, so it is wide whatever the other axis.
  constexpr double kSurelyWide = kMaxBilinearPoints + 2;
  if (x.width() >= kSurelyWide || y.width() >= kSurelyWide) return everyValue();
  if (model_.decodingPinned || !shading_.blockCompressed) {
    // The common box: inside one cell between texel centres on both axes (a box narrower than a
    // texel mostly is), where the stops are its ends alone.
    const double cx0 = std::floor(x.lo - 0.5), cy0 = std::floor(y.lo - 0.5);
    if (cx0 == std::floor(x.hi - 0.5) && cy0 == std::floor(y.hi - 0.5))
      return bilinearInCell(x, y, cx0, cy0);
  }
  // Per axis the stops: the box's ends and the texel centres strictly inside.
  BilinearStops xs, ys;
  if (!xs.of(x) || !ys.of(y) || xs.count * ys.count > kMaxBilinearPoints) return texelHull(x, y);
  return bilinearAtStops(x, y, xs, ys);
}

void Builder::fetchRange(glm::ivec2 at, TexelRange& r) {
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
}

Colour Builder::texelHull(Interval x, Interval y) {
  // A wide box: every texel it reaches bounds the filter (a convex combination of them); beyond
  // 16 x 16 texels, the whole range (cheaper than reading them, and still a bound).
  if (y.width() > 16 || x.width() > 16) return everyValue();
  TexelHull hull;
  for (int ty = static_cast<int>(std::floor(y.lo - 0.5));
       ty <= static_cast<int>(std::floor(y.hi - 0.5)) + 1; ++ty)
    for (int tx = static_cast<int>(std::floor(x.lo - 0.5));
         tx <= static_cast<int>(std::floor(x.hi - 0.5)) + 1; ++tx) {
      TexelRange v;
      fetchRange({tx, ty}, v);
      hull.include(v);
    }
  return hull.colour();
}

Colour Builder::bilinearAtStops(Interval x, Interval y, const BilinearStops& xs,
                                const BilinearStops& ys) {
  // The texels the stops read, each fetched once: a box spans at most one cell more than it
  // has stops per axis, so (xs + 1) (ys + 1) <= 99 texels with xs ys <= 64 and both at least 2.
  const glm::ivec2 origin(static_cast<int>(std::floor(x.lo - 0.5)),
                          static_cast<int>(std::floor(y.lo - 0.5)));
  const int width = static_cast<int>(std::floor(x.hi - 0.5)) + 2 - origin.x;
  const int height = static_cast<int>(std::floor(y.hi - 0.5)) + 2 - origin.y;
  constexpr int kMaxTexels = 128;
  if (width * height > kMaxTexels)  // never (see above); a bound all the same
    return everyValue();
  std::array<TexelRange, kMaxTexels> block;
  for (int ty = 0; ty < height; ++ty)
    for (int tx = 0; tx < width; ++tx)
      fetchRange(origin + glm::ivec2(tx, ty), block[static_cast<size_t>(ty * width + tx)]);
  // Texels that are one value (no free block decoding) need the least bounds only: the greatest
  // are the same operations on the same values.
  const size_t channels = !model_.decodingPinned && shading_.blockCompressed ? 8 : 4;
  // Per x stop, each texel row's value along x; then per y stop the lerp between two rows. The
  // filter's weights are not negative: it grows with every texel, so its least value comes from
  // the least texels and its greatest from the greatest.
  TexelHull hull;
  std::array<TexelRange, kMaxTexels> rows;
  for (size_t i = 0; i < xs.count; ++i) {
    const double tx = xs.at[i] - 0.5;
    const double bx = std::floor(tx), fx = tx - bx;
    const int column = static_cast<int>(bx) - origin.x;
    for (int ty = 0; ty < height; ++ty) {
      const TexelRange& c0 = block[static_cast<size_t>(ty * width + column)];
      const TexelRange& c1 = block[static_cast<size_t>(ty * width + column + 1)];
      TexelRange& row = rows[static_cast<size_t>(ty)];
      for (size_t k = 0; k < channels; ++k) row[k] = c0[k] + (c1[k] - c0[k]) * fx;
    }
    for (size_t j = 0; j < ys.count; ++j) {
      const double ty = ys.at[j] - 0.5;
      const double by = std::floor(ty), fy = ty - by;
      const TexelRange& row0 = rows[static_cast<size_t>(static_cast<int>(by) - origin.y)];
      const TexelRange& row1 = rows[static_cast<size_t>(static_cast<int>(by) - origin.y + 1)];
      TexelRange value;
      for (size_t k = 0; k < channels; ++k) value[k] = row0[k] + (row1[k] - row0[k]) * fy;
      if (channels == 4)
        for (size_t k = 0; k < 4; ++k) value[k + 4] = value[k];
      hull.include(value);
    }
  }
  if (cornerStep_ == 0) return hull.colour();
  // The corner rounding of any cell the box reads: its texels' own, or with free decoding
  // the bound over any values.
  glm::dvec4 rounding(channels == 8 ? worstCornerRounding() : 0.0);
  if (channels == 4)
    for (int ty = 0; ty + 1 < height; ++ty)
      for (int tx = 0; tx + 1 < width; ++tx) {
        const auto at = [&](int dx, int dy) {
          const TexelRange& r = block[static_cast<size_t>((ty + dy) * width + tx + dx)];
          return glm::dvec4(r[0], r[1], r[2], r[3]);
        };
        rounding = glm::max(rounding, cornerRounding(at(0, 0), at(1, 0), at(0, 1), at(1, 1)));
      }
  const Colour c = hull.colour();
  return {c.lo - rounding, c.hi + rounding};
}

Colour Builder::bilinearInCell(Interval x, Interval y, double cx0, double cy0) {
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

void Builder::store(const Colour& c, glm::u8vec4& lo, glm::u8vec4& hi) const {
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

}  // namespace vt::reference::sets
