#pragma once
// Closed intervals of reals for the oracle's result sets (result_set.h), in double.
//
// The quantities bounded come from float data (window positions, attributes, texels) and the
// widths that matter are float-sized (2^-23 relative and up). Each operation here is one double
// operation rounded to nearest, an error of at most 2^-53 relative per bound; `widen` adds 2^-40
// relative after every composite step, which covers more than 8,000 such roundings. So the
// intervals are conservative without directed rounding.

#include <algorithm>
#include <cmath>
#include <limits>

namespace vt::reference {

// The relative slack every composite step adds (widen), and every bound built in double from float
// data: a double operation rounds by at most 2^-53 relative, so 2^-40 covers 2^13 = 8,192 of them
// in one step, far more than any step here performs, and stays far below the 2^-23 widths of the
// float quantities the sets bound.
inline constexpr double kDoubleSlack = 0x1p-40;

struct Interval {
  double lo = 0, hi = 0;

  static Interval point(double x) { return {x, x}; }
  static Interval around(double x, double radius) { return {x - radius, x + radius}; }
  static Interval everything() {
    return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }

  bool contains(double x) const { return lo <= x && x <= hi; }
  bool containsZero() const { return lo <= 0 && hi >= 0; }
  bool finite() const { return std::isfinite(lo) && std::isfinite(hi); }
  double width() const { return hi - lo; }
  double magnitude() const { return std::max(std::fabs(lo), std::fabs(hi)); }
};

inline Interval operator+(Interval a, Interval b) { return {a.lo + b.lo, a.hi + b.hi}; }
inline Interval operator-(Interval a, Interval b) { return {a.lo - b.hi, a.hi - b.lo}; }
inline Interval operator-(Interval a) { return {-a.hi, -a.lo}; }
inline Interval operator*(Interval a, Interval b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}
// The same as a * Interval::point(s): its four products are two, each twice.
inline Interval operator*(Interval a, double s) {
  const double l = a.lo * s, h = a.hi * s;
  return {std::min(l, h), std::max(l, h)};
}
// a / b; everything when b may be zero.
inline Interval operator/(Interval a, Interval b) {
  if (b.containsZero()) return Interval::everything();
  return a * Interval{1.0 / b.hi, 1.0 / b.lo};
}

inline Interval hull(Interval a, Interval b) {
  return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}

// Widened by `relative` of its magnitude and by `absolute`, plus kDoubleSlack relative.
inline Interval widen(Interval a, double relative = 0, double absolute = 0) {
  const double r = (relative + kDoubleSlack) * a.magnitude() + absolute;
  return {a.lo - r, a.hi + r};
}

// max(a, b) of two intervals, and the monotonic functions the LOD uses.
inline Interval max(Interval a, Interval b) { return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)}; }
inline Interval square(Interval a) {
  if (a.containsZero()) return {0, std::max(a.lo * a.lo, a.hi * a.hi)};
  return {std::min(a.lo * a.lo, a.hi * a.hi), std::max(a.lo * a.lo, a.hi * a.hi)};
}
inline Interval sqrt(Interval a) {
  return {std::sqrt(std::max(a.lo, 0.0)), std::sqrt(std::max(a.hi, 0.0))};
}
inline Interval log2(Interval a) {
  return {a.lo > 0 ? std::log2(a.lo) : -std::numeric_limits<double>::infinity(),
          a.hi > 0 ? std::log2(a.hi) : -std::numeric_limits<double>::infinity()};
}
inline Interval clamp(Interval a, double lo, double hi) {
  return {std::clamp(a.lo, lo, hi), std::clamp(a.hi, lo, hi)};
}

}  // namespace vt::reference
