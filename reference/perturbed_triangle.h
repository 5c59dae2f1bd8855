#pragma once
// Bounds on what a triangle's interpolated values can be when each of its corners may lie anywhere
// within `radius` (in x and in y) of its nominal window position: the snapping of a precision model
// that does not pin the sub-pixel grid (result_set_builder.h).
//
// The bounds are exact to first order instead of interval arithmetic over the corners (whose
// barycentrics, ratios and differences of correlated values lose orders of magnitude). They rest on
// one identity. Let c_j be the nominal corners, c'_j the moved ones, lambda and lambda' the
// barycentric coordinates of the two triangles, and phi the affine map with phi(c'_j) = c_j. Affine
// maps keep barycentric coordinates, so lambda'(p) = lambda(phi(p)), and every value interpolated
// from per-corner data (window z linearly, s/w, t/w and 1/w alike, hence s = (s/w) / (1/w)) of the
// moved triangle at p is the nominal triangle's value at phi(p). With
//   phi(p) - p = sum_j lambda'_j(p) (c_j - c'_j),     |c_j - c'_j| <= r per axis,
// phi(p) lies within r * sum_j |lambda'_j(p)| of p, and |lambda'_j(p)| <= |lambda_j(p)| +
// |grad lambda_j|_1 |phi(p) - p| gives, with G = sum_j |grad lambda_j|_1 of the nominal triangle,
//   |phi(p) - p| <= rho0(p) = r * sum_j |lambda_j(p)| / (1 - r G).
// A step by one pixel along axis a moves phi by that pixel plus
//   phi(p + e_a) - phi(p) - e_a = sum_j (d lambda'_j / d a) (c_j - c'_j),
// each component within rho1_a = r * sum_j |d lambda_j / d a| / (1 - r G) (the same argument on the
// gradients). A triangle with r G >= 1/2 (smaller than about a pixel's eighth per radius) gets no
// bounds here: the caller falls back to interval arithmetic.
//
// A fine derivative of the moved triangle is then the nominal value's difference between two
// points q and q + e_a + eps, q in the box around p, |eps| <= rho1_a: the mean-value theorem bounds
// it by the nominal gradient over a box a little larger than one pixel. The nominal planes are
// computed in double from the float corners; each bound is widened by 2^-40 of the magnitudes of
// the terms it sums, which covers their rounding (a few units of 2^-53 each) many times over.

#include <array>
#include <cmath>

#include "reference/interval.h"
#include "reference/triangle_setup.h"

namespace vt::reference {

// v(x, y) = a0 + ax x + ay y in window coordinates (pixel centres at + 0.5).
struct AffinePlane {
  double a0 = 0, ax = 0, ay = 0;
  double at(double x, double y) const { return a0 + ax * x + ay * y; }
};

// An axis-aligned box of window positions.
struct WindowBox {
  Interval x, y;
};

class PerturbedTriangle {
 public:
  // `radius`: how far each corner may lie from its nominal position, per axis.
  PerturbedTriangle(const SetupTriangle& t, double radius);

  // False when the triangle is too small for first-order bounds (r G >= 1/2) or degenerate.
  bool bounded() const { return bounded_; }

  // Where phi(p) lies for the pixel centre p = (cx, cy).
  WindowBox sourceBox(double cx, double cy) const;
  // A box that holds sourceBox(cx, cy) as computed, for every centre in [x0, x1] x [y0, y1]: the
  // growth is convex in the centre, so its largest value lies at a corner; a sixteenth of the
  // corners' rounding term covers the few units of 2^-53 by which a centre inside may compute
  // above them. Bounds over it hold at each centre: the interval evaluations here are monotone in
  // their box, rounding to nearest included.
  WindowBox sourceBoxOver(double x0, double y0, double x1, double y1) const;

  // lambda' at the centre: the barycentric coordinates of the moved triangle.
  std::array<Interval, 3> barycentrics(double cx, double cy) const;
  // Window z of the moved triangle at the centre.
  Interval depth(double cx, double cy) const;

  // A perspective-correct attribute (numerator plane over 1/w) at the centre, and its fine
  // derivative along x (axis 0) or y (axis 1): from the centre (cx, cy) to the next pixel's.
  // Everything where 1/w may vanish.
  Interval ratio(const AffinePlane& numerator, double cx, double cy) const;

  // The same three from a centre's sourceBox, for a caller that needs several at one centre.
  std::array<Interval, 3> barycentrics(const WindowBox& source) const;
  Interval barycentric(size_t i, const WindowBox& source) const;  // lambda'_i alone
  Interval depth(const WindowBox& source) const;
  Interval ratio(const AffinePlane& numerator, const WindowBox& source) const;
  Interval ratioStep(const AffinePlane& numerator, double cx, double cy, int axis) const;
  // Two attributes at once (s and t), sharing 1/w's evaluations: each the same as alone.
  std::array<Interval, 2> ratios(const AffinePlane& a, const AffinePlane& b,
                                 const WindowBox& source) const;
  std::array<Interval, 2> ratioSteps(const AffinePlane& a, const AffinePlane& b, double cx,
                                     double cy, int axis) const;

  // The plane through the corners' s/w (or t/w).
  AffinePlane attribute(const std::array<float, 3>& values) const;

  // How a perspective-correct attribute f = numerator / (1/w) of the nominal triangle varies over
  // a box of window positions: upper bounds of |f|, of its gradient's components (f_x = N_x / w^2,
  // N_x = (nx w0 - n0 wx) + C y, C = nx wy - ny wx; f_y = N_y / w^2, N_y = (ny w0 - n0 wy) - C x;
  // as derivativesNear bounds them) and of 1 / (1/w)^2. `scale` bounds ratioScale at every centre
  // of [x0, x1] x [y0, y1] (inside the box): the terms T are convex, largest at a corner, and |f|
  // and 1 / |1/w| are at most their bounds over the box. Not finite where 1/w may vanish over the
  // box.
  struct RatioOver {
    double magnitude = 0, scale = 0;
    double inverseW2 = 0;              // sup 1 / (1/w)^2
    std::array<double, 2> gradient{};  // sup |f_x|, sup |f_y|
    bool finite = false;
  };
  RatioOver ratioOver(const AffinePlane& numerator, const WindowBox& box, double x0, double y0,
                      double x1, double y1) const;
  // Bounds of f = numerator / (1/w) near one centre (cx, cy), from the planes' slopes over a small
  // box (|N_x|, |N_y| and |1/w| move by at most their planes' slopes times the box's half sizes;
  // then as ratioOver), for the bounds of one pixel:
  //   - ratioReach: how far f moves over the box of half size rho around the centre (its source
  //     box): at most (sup |f_x| + sup |f_y|) rho there;
  //   - ratioStepReach: how far a moved fine step along `axis` from the centre, whose source box
  //     reaches rho, lies from the nominal f_x (f_y) at the step's middle: the step is the nominal
  //     derivative somewhere in the box from the first centre's source box to the far end moved
  //     by e (1 + 2 rho + 2 e along the axis, 2 rho + 2 e across, e = stepRadius), plus at most
  //     (sup |f_x| + sup |f_y|) e (the header): within f_xx (1/2 + rho + e) + f_xy (rho + e) +
  //     (|f_x| + |f_y|) e of the middle's; `slope` bounds the step's magnitude.
  // Infinite where 1/w may vanish in the box.
  double ratioReach(const AffinePlane& numerator, double cx, double cy, double rho) const;
  struct StepReach {
    double width, slope;
  };
  StepReach ratioStepReach(const AffinePlane& numerator, int axis, double cx, double cy,
                           double rho) const;

  // The plane of 1/w through the corners (the denominator of every ratio).
  const AffinePlane& oneOverW() const { return oneOverW_; }
  // rho1 of the header along an axis: how far a fine step's far end may move beyond one pixel.
  double stepRadius(int axis) const { return stepRadius_[static_cast<size_t>(axis)]; }

  // The size of the terms an implementation sums to evaluate numerator / (1/w) at the centre in
  // float: (T(n) + |n / w| T(1/w)) / |1/w|, with T(plane) = |a(o)| + |ax (x - ox)| + |ay (y - oy)|
  // for the plane's origin o at the window's origin or at a corner, whichever is larger. A
  // float evaluation errs relative to this, not to the value, which cancellation makes small
  // (near a horizon, 1/w is a small difference of large terms).
  double ratioScale(const AffinePlane& numerator, double cx, double cy) const;
  // The size of the terms an evaluation of window z sums at the centre, T(z) as above (infinite
  // where the plane is not finite). Defined whenever the nominal triangle has an area, bounded()
  // or not: the plane of the nominal corners, which differs from a moved one's by second order.
  double depthTerms(double cx, double cy) const;
  std::array<double, 2> ratioScales(const AffinePlane& a, const AffinePlane& b, double cx,
                                    double cy) const;

 private:
  Interval affineOver(const AffinePlane& plane, const WindowBox& box) const;
  // The gradient of numerator / (1/w) over a box, per axis, given the reciprocal of 1/w's square
  // over it.
  std::array<Interval, 2> ratioGradient(const AffinePlane& numerator, const WindowBox& box,
                                        Interval inverseW2) const;

  double terms(const AffinePlane& plane, double cx, double cy) const;
  // Upper bounds of |f_x|, |f_y|, |f_xx|, |f_xy|, |f_yx|, |f_yy| over the box (mx, my) +- (hx, hy)
  // (ratioReach); infinite where 1/w may vanish there.
  std::array<double, 6> derivativesNear(const AffinePlane& numerator, double mx, double my,
                                        double hx, double hy) const;
  // What the source box at centre (cx, cy) grows by, before radius and shrink: sum_j
  // |lambda_j| and the rounding of its evaluation (sourceBox, sourceBoxOver).
  struct Growth {
    double sum, rounding;
  };
  Growth growthAt(double cx, double cy) const;

  std::array<AffinePlane, 3> lambda_;
  std::array<double, 3> cornerX_{}, cornerY_{};
  AffinePlane z_, oneOverW_;
  double radius_ = 0, shrink_ = 1;      // shrink_ = 1 / (1 - r G)
  std::array<double, 2> stepRadius_{};  // rho1 per axis
  bool bounded_ = false;
};

// The small bounds every pixel asks for, here so that callers inline them (always: called apart,
// their intervals travel through the stack, a stall on every call).
namespace perturbed_detail {

// The rounding of a double evaluation, absolute, from the magnitudes of its terms (kDoubleSlack of
// them: far below every radius the bounds carry).
inline double slack(const AffinePlane& p, const WindowBox& box) {
  return kDoubleSlack * (std::fabs(p.a0) + std::fabs(p.ax) * box.x.magnitude() +
                         std::fabs(p.ay) * box.y.magnitude());
}

inline WindowBox grown(const WindowBox& box, double by) {
  return {{box.x.lo - by, box.x.hi + by}, {box.y.lo - by, box.y.hi + by}};
}

}  // namespace perturbed_detail

[[gnu::always_inline]] inline PerturbedTriangle::Growth PerturbedTriangle::growthAt(
    double cx, double cy) const {
  Growth g{0, 0};
  for (const AffinePlane& l : lambda_) g.sum += std::fabs(l.at(cx, cy));
  const WindowBox centre{Interval::point(cx), Interval::point(cy)};
  for (const AffinePlane& l : lambda_) g.rounding += perturbed_detail::slack(l, centre);
  return g;
}

[[gnu::always_inline]] inline WindowBox PerturbedTriangle::sourceBox(double cx, double cy) const {
  const Growth g = growthAt(cx, cy);
  const WindowBox centre{Interval::point(cx), Interval::point(cy)};
  return perturbed_detail::grown(centre, radius_ * (g.sum + g.rounding) * shrink_);
}

[[gnu::always_inline]] inline Interval PerturbedTriangle::affineOver(const AffinePlane& p,
                                                                     const WindowBox& box) const {
  // Each variable once: interval evaluation of an affine function is exact.
  const Interval v = Interval::point(p.a0) + box.x * p.ax + box.y * p.ay;
  return widen(v, 0, perturbed_detail::slack(p, box));
}

inline Interval PerturbedTriangle::barycentric(size_t i, const WindowBox& box) const {
  return affineOver(lambda_[i], box);
}

inline Interval PerturbedTriangle::depth(const WindowBox& box) const { return affineOver(z_, box); }

}  // namespace vt::reference
