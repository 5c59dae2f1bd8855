// What the shader computes of one candidate at one pixel, as intervals (set_builder.h): (s, t),
// the fine derivatives over its quad and the LOD, and from them the candidate's alternative.

#include <algorithm>
#include <cmath>

#include "reference/set_builder.h"

namespace vt::reference::sets {

FragmentRange Builder::fragment(const SetupTriangle& t, Snapped* snapped, int px, int py) const {
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

Alternative Builder::alternative(const SetupTriangle& t, int32_t index, const FragmentRange& f,
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
        shade(clamp(Interval::point(oracle.uv.x), 0, 1), clamp(Interval::point(oracle.uv.y), 0, 1),
              Interval::point(oracle.lod));
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

void Builder::setUv(Interval s, Interval t, Alternative& a) {
  a.uvLo = glm::vec2(static_cast<float>(s.lo), static_cast<float>(t.lo));
  a.uvHi = glm::vec2(static_cast<float>(s.hi), static_cast<float>(t.hi));
  a.uvLo = glm::vec2(std::nextafter(a.uvLo.x, -1.0f), std::nextafter(a.uvLo.y, -1.0f));
  a.uvHi = glm::vec2(std::nextafter(a.uvHi.x, 2.0f), std::nextafter(a.uvHi.y, 2.0f));
}

Interval Builder::lodRange(Interval dsdx, Interval dtdx, Interval dsdy, Interval dtdy) const {
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

}  // namespace vt::reference::sets
