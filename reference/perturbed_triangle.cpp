#include "reference/perturbed_triangle.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vt::reference {

using perturbed_detail::grown;
using perturbed_detail::slack;

PerturbedTriangle::PerturbedTriangle(const SetupTriangle& t, double radius) : radius_(radius) {
  std::array<double, 3> x, y;
  for (size_t i = 0; i < 3; ++i) {
    x[i] = cornerX_[i] = t.corners[i].x;
    y[i] = cornerY_[i] = t.corners[i].y;
  }
  // Differences and products of floats are exact in double; the area rounds once.
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  if (!std::isfinite(area) || area == 0) return;
  double g = 0, gx = 0, gy = 0;
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3, k = (i + 2) % 3;
    // lambda_i(p) = ((x_k - x_j) (p_y - y_j) - (y_k - y_j) (p_x - x_j)) / area
    lambda_[i].ax = -(y[k] - y[j]) / area;
    lambda_[i].ay = (x[k] - x[j]) / area;
    lambda_[i].a0 = ((y[k] - y[j]) * x[j] - (x[k] - x[j]) * y[j]) / area;
    gx += std::fabs(lambda_[i].ax);
    gy += std::fabs(lambda_[i].ay);
  }
  g = gx + gy;
  z_ = attribute({t.corners[0].z, t.corners[1].z, t.corners[2].z});
  if (!std::isfinite(g) || !(radius * g < 0.5)) return;
  shrink_ = 1 / (1 - radius * g);
  stepRadius_ = {radius * gx * shrink_, radius * gy * shrink_};
  oneOverW_ = attribute({t.corners[0].oow, t.corners[1].oow, t.corners[2].oow});
  bounded_ = std::isfinite(z_.a0) && std::isfinite(oneOverW_.a0);
}

AffinePlane PerturbedTriangle::attribute(const std::array<float, 3>& values) const {
  AffinePlane p;
  for (size_t i = 0; i < 3; ++i) {
    p.a0 += values[i] * lambda_[i].a0;
    p.ax += values[i] * lambda_[i].ax;
    p.ay += values[i] * lambda_[i].ay;
  }
  return p;
}

double PerturbedTriangle::terms(const AffinePlane& p, double cx, double cy) const {
  double largest = std::fabs(p.a0) + std::fabs(p.ax * cx) + std::fabs(p.ay * cy);
  for (size_t i = 0; i < 3; ++i)
    largest = std::max(largest, std::fabs(p.at(cornerX_[i], cornerY_[i])) +
                                    std::fabs(p.ax * (cx - cornerX_[i])) +
                                    std::fabs(p.ay * (cy - cornerY_[i])));
  return largest;
}

double PerturbedTriangle::depthTerms(double cx, double cy) const {
  const double t = terms(z_, cx, cy);
  return std::isfinite(t) ? t : std::numeric_limits<double>::infinity();
}

double PerturbedTriangle::ratioScale(const AffinePlane& numerator, double cx, double cy) const {
  return ratioScales(numerator, numerator, cx, cy)[0];
}

std::array<double, 2> PerturbedTriangle::ratioScales(const AffinePlane& a, const AffinePlane& b,
                                                     double cx, double cy) const {
  const double w = std::fabs(oneOverW_.at(cx, cy));
  const double wTerms = terms(oneOverW_, cx, cy);
  const auto scale = [&](const AffinePlane& numerator) {
    const double value = std::fabs(numerator.at(cx, cy)) / w;
    return (terms(numerator, cx, cy) + value * wTerms) / w;
  };
  return {scale(a), scale(b)};
}

PerturbedTriangle::RatioOver PerturbedTriangle::ratioOver(const AffinePlane& n,
                                                          const WindowBox& box, double x0,
                                                          double y0, double x1, double y1) const {
  RatioOver r;
  const AffinePlane& w = oneOverW_;
  const Interval wRange = affineOver(w, box);
  if (wRange.containsZero() || !wRange.finite()) return r;
  // Every bound below is a handful of double operations on magnitudes: 2^-40 of each covers their
  // rounding many times over.
  constexpr double kUp = 1 + kDoubleSlack;
  const double wMin = std::min(std::fabs(wRange.lo), std::fabs(wRange.hi)) / kUp;
  const double inverse = 1 / wMin;
  // A ratio of affine functions is monotonic along every line where 1/w keeps its sign: |f| is
  // largest at a corner of the box.
  for (double x : {box.x.lo, box.x.hi})
    for (double y : {box.y.lo, box.y.hi})
      r.magnitude = std::max(r.magnitude, std::fabs(n.at(x, y) / w.at(x, y)));
  r.magnitude = r.magnitude * kUp + (slack(n, box) + r.magnitude * slack(w, box)) * inverse;
  r.inverseW2 = inverse * inverse * kUp;
  // The gradient over the box as around its middle (derivativesNear), the half sizes grown past
  // the rounding of the middle and of the halves (an ulp of the coordinates each).
  const double hx = box.x.width() / 2 + 0x1p-50 * box.x.magnitude();
  const double hy = box.y.width() / 2 + 0x1p-50 * box.y.magnitude();
  const std::array<double, 6> d =
      derivativesNear(n, (box.x.lo + box.x.hi) / 2, (box.y.lo + box.y.hi) / 2, hx, hy);
  r.gradient = {d[0], d[1]};
  double nTerms = 0, wTerms = 0;
  for (double cx : {x0, x1})
    for (double cy : {y0, y1}) {
      nTerms = std::max(nTerms, terms(n, cx, cy));
      wTerms = std::max(wTerms, terms(w, cx, cy));
    }
  r.scale = (nTerms + r.magnitude * wTerms) * inverse * kUp;
  r.finite = std::isfinite(r.scale) && std::isfinite(r.gradient[0]) && std::isfinite(r.gradient[1]);
  return r;
}

std::array<double, 6> PerturbedTriangle::derivativesNear(const AffinePlane& n, double mx, double my,
                                                         double hx, double hy) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kUp = 1 + kDoubleSlack;
  const AffinePlane& w = oneOverW_;
  const double wMin =
      (std::fabs(w.at(mx, my)) - (std::fabs(w.ax) * hx + std::fabs(w.ay) * hy)) / kUp;
  if (!(wMin > 0)) return {kInf, kInf, kInf, kInf, kInf, kInf};
  const double cross = n.ax * w.ay - n.ay * w.ax, c = std::fabs(cross);
  // N_x = (nx w0 - n0 wx) + C y and N_y = (ny w0 - n0 wy) - C x, with their rounding.
  const double nx =
      (std::fabs(n.ax * w.a0 - n.a0 * w.ax + cross * my) + c * hy) * kUp +
      kDoubleSlack * (std::fabs(n.ax * w.a0) + std::fabs(n.a0 * w.ax) + c * (std::fabs(my) + hy));
  const double ny =
      (std::fabs(n.ay * w.a0 - n.a0 * w.ay - cross * mx) + c * hx) * kUp +
      kDoubleSlack * (std::fabs(n.ay * w.a0) + std::fabs(n.a0 * w.ay) + c * (std::fabs(mx) + hx));
  const double i2 = kUp / (wMin * wMin), i3 = i2 * kUp / wMin;
  return {nx * i2 * kUp,
          ny * i2 * kUp,
          2 * std::fabs(w.ax) * nx * i3 * kUp,
          (c * i2 + 2 * std::fabs(w.ay) * nx * i3) * kUp,
          (c * i2 + 2 * std::fabs(w.ax) * ny * i3) * kUp,
          2 * std::fabs(w.ay) * ny * i3 * kUp};
}

double PerturbedTriangle::ratioReach(const AffinePlane& n, double cx, double cy, double rho) const {
  const std::array<double, 6> d = derivativesNear(n, cx, cy, rho, rho);
  return (d[0] + d[1]) * rho * (1 + kDoubleSlack);
}

PerturbedTriangle::StepReach PerturbedTriangle::ratioStepReach(const AffinePlane& n, int axis,
                                                               double cx, double cy,
                                                               double rho) const {
  const double e = stepRadius_[static_cast<size_t>(axis)];
  const double along = 0.5 + rho + e, across = rho + e;
  const std::array<double, 6> d = axis == 0 ? derivativesNear(n, cx + 0.5, cy, along, across)
                                            : derivativesNear(n, cx, cy + 0.5, across, along);
  const double g = d[0] + d[1];
  const double width =
      axis == 0 ? d[2] * along + d[3] * across + g * e : d[5] * along + d[4] * across + g * e;
  return {width * (1 + kDoubleSlack), (d[static_cast<size_t>(axis)] + g * e) * (1 + kDoubleSlack)};
}

WindowBox PerturbedTriangle::sourceBoxOver(double x0, double y0, double x1, double y1) const {
  double inner = 0, roundings = 0;
  for (double cx : {x0, x1})
    for (double cy : {y0, y1}) {
      const Growth g = growthAt(cx, cy);
      inner = std::max(inner, g.sum + g.rounding);
      roundings = std::max(roundings, g.rounding);
    }
  const double by = radius_ * (inner + roundings / 16) * shrink_;
  return {{x0 - by, x1 + by}, {y0 - by, y1 + by}};
}

std::array<Interval, 3> PerturbedTriangle::barycentrics(double cx, double cy) const {
  return barycentrics(sourceBox(cx, cy));
}

std::array<Interval, 3> PerturbedTriangle::barycentrics(const WindowBox& box) const {
  return {affineOver(lambda_[0], box), affineOver(lambda_[1], box), affineOver(lambda_[2], box)};
}

Interval PerturbedTriangle::depth(double cx, double cy) const { return depth(sourceBox(cx, cy)); }

Interval PerturbedTriangle::ratio(const AffinePlane& numerator, double cx, double cy) const {
  return ratio(numerator, sourceBox(cx, cy));
}

Interval PerturbedTriangle::ratio(const AffinePlane& numerator, const WindowBox& box) const {
  return ratios(numerator, numerator, box)[0];
}

std::array<Interval, 2> PerturbedTriangle::ratios(const AffinePlane& a, const AffinePlane& b,
                                                  const WindowBox& box) const {
  const Interval w = affineOver(oneOverW_, box);
  if (w.containsZero()) return {Interval::everything(), Interval::everything()};
  // A ratio of two affine functions is monotonic along every line where its denominator keeps its
  // sign: over a box its bounds lie at the corners.
  const double inf = std::numeric_limits<double>::infinity();
  std::array<double, 2> lo{inf, inf}, hi{-inf, -inf};
  for (double x : {box.x.lo, box.x.hi})
    for (double y : {box.y.lo, box.y.hi}) {
      const double d = oneOverW_.at(x, y);
      const double va = a.at(x, y) / d, vb = b.at(x, y) / d;
      lo = {std::min(lo[0], va), std::min(lo[1], vb)};
      hi = {std::max(hi[0], va), std::max(hi[1], vb)};
    }
  const double wMin = std::min(std::fabs(w.lo), std::fabs(w.hi));
  const double wSlack = slack(oneOverW_, box);
  const auto bound = [&](const AffinePlane& n, double l, double h) {
    const double rounding = (slack(n, box) + std::max(std::fabs(l), std::fabs(h)) * wSlack) / wMin;
    return widen({l, h}, kDoubleSlack, rounding);
  };
  return {bound(a, lo[0], hi[0]), bound(b, lo[1], hi[1])};
}

std::array<Interval, 2> PerturbedTriangle::ratioGradient(const AffinePlane& n, const WindowBox& box,
                                                         Interval inverseW2) const {
  const AffinePlane& w = oneOverW_;
  // d/dx (n / w) = ((nx w0 - n0 wx) + (nx wy - ny wx) y) / w^2, and alike for y.
  const double cross = n.ax * w.ay - n.ay * w.ax;
  const Interval numX = Interval::point(n.ax * w.a0 - n.a0 * w.ax) + box.y * cross;
  const Interval numY = Interval::point(n.ay * w.a0 - n.a0 * w.ay) - box.x * cross;
  const double termsX = std::fabs(n.ax * w.a0) + std::fabs(n.a0 * w.ax) +
                        (std::fabs(n.ax * w.ay) + std::fabs(n.ay * w.ax)) * box.y.magnitude();
  const double termsY = std::fabs(n.ay * w.a0) + std::fabs(n.a0 * w.ay) +
                        (std::fabs(n.ax * w.ay) + std::fabs(n.ay * w.ax)) * box.x.magnitude();
  return {widen(widen(numX, 0, kDoubleSlack * termsX) * inverseW2, kDoubleSlack),
          widen(widen(numY, 0, kDoubleSlack * termsY) * inverseW2, kDoubleSlack)};
}

Interval PerturbedTriangle::ratioStep(const AffinePlane& numerator, double cx, double cy,
                                      int axis) const {
  return ratioSteps(numerator, numerator, cx, cy, axis)[0];
}

std::array<Interval, 2> PerturbedTriangle::ratioSteps(const AffinePlane& a, const AffinePlane& b,
                                                      double cx, double cy, int axis) const {
  const WindowBox from = sourceBox(cx, cy);
  // q in `from`, the step's far end at q + e_axis + eps: the box around both ends.
  WindowBox around = from;
  (axis == 0 ? around.x.hi : around.y.hi) += 1;
  const double eps = stepRadius_[static_cast<size_t>(axis)];
  around = grown(around, eps);
  const Interval wRange = affineOver(oneOverW_, around);
  if (wRange.containsZero()) return {Interval::everything(), Interval::everything()};
  const Interval w2 = square(wRange);
  if (w2.containsZero()) return {Interval::everything(), Interval::everything()};
  // Dividing by w2 is multiplying by this (interval.h), once for the four quotients.
  const Interval inverseW2{1.0 / w2.hi, 1.0 / w2.lo};
  const auto step = [&](const AffinePlane& numerator) {
    const std::array<Interval, 2> gradient = ratioGradient(numerator, around, inverseW2);
    if (!gradient[0].finite() || !gradient[1].finite()) return Interval::everything();
    // n/w(q + e) - n/w(q) by the mean-value theorem along the step; plus n/w(q + e + eps) -
    // n/w(q + e), within the gradient's magnitude times eps.
    const double moved = (gradient[0].magnitude() + gradient[1].magnitude()) * eps;
    return widen(gradient[static_cast<size_t>(axis)], 0, moved);
  };
  return {step(a), step(b)};
}

}  // namespace vt::reference
