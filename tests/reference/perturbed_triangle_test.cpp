// PerturbedTriangle's bounds: every triangle whose corners lie within the radius of the nominal
// ones has its values (barycentrics, window z, perspective-correct attributes and their fine
// derivatives) inside them, at pixels inside and outside it (helpers), and the bounds are tight
// where the triangle is large (first order: the radius times the gradient, not more).
#include "reference/perturbed_triangle.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

namespace vt::reference {
namespace {

struct Moved {
  std::array<long double, 3> x, y;
};

// The moved triangle's barycentric coordinates at (px, py), in long double.
std::array<long double, 3> barycentricsOf(const Moved& m, long double px, long double py) {
  const long double area =
      (m.x[1] - m.x[0]) * (m.y[2] - m.y[0]) - (m.x[2] - m.x[0]) * (m.y[1] - m.y[0]);
  std::array<long double, 3> l;
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3, k = (i + 2) % 3;
    l[i] = ((m.x[k] - m.x[j]) * (py - m.y[j]) - (m.y[k] - m.y[j]) * (px - m.x[j])) / area;
  }
  return l;
}

long double interpolated(const std::array<long double, 3>& l, float a, float b, float c) {
  return l[0] * a + l[1] * b + l[2] * c;
}

long double ratioAt(const Moved& m, const SetupTriangle& t, long double px, long double py) {
  const auto l = barycentricsOf(m, px, py);
  return interpolated(l, t.corners[0].sw, t.corners[1].sw, t.corners[2].sw) /
         interpolated(l, t.corners[0].oow, t.corners[1].oow, t.corners[2].oow);
}

bool inside(Interval i, long double v) {
  // The long double reference carries its own rounding, far below the bounds' slack.
  const long double tolerance = 1e-12L * (1 + std::fabs(v));
  return i.lo - tolerance <= v && v <= i.hi + tolerance;
}

SetupTriangle randomTriangle(std::mt19937& rng, double size) {
  std::uniform_real_distribution<float> position(-50.0f, 350.0f), unit(0.0f, 1.0f),
      depth(0.1f, 10.0f), offset(static_cast<float>(-size), static_cast<float>(size));
  SetupTriangle t;
  const float cx = position(rng), cy = position(rng);
  for (WindowCorner& c : t.corners) {
    c.x = cx + offset(rng);
    c.y = cy + offset(rng);
    c.z = unit(rng);
    c.oow = 1.0f / depth(rng);
    c.sw = unit(rng) * c.oow;
    c.tw = unit(rng) * c.oow;
  }
  return t;
}

TEST(PerturbedTriangle, EveryMovedTriangleLiesInsideTheBounds) {
  std::mt19937 rng(7);
  constexpr double kRadius = 1.0 / 16;
  std::uniform_real_distribution<double> move(-kRadius, kRadius);
  std::bernoulli_distribution extreme(0.5);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const SetupTriangle t = randomTriangle(rng, trial % 4 == 0 ? 4.0 : 120.0);
    const PerturbedTriangle bounds(t, kRadius);
    if (!bounds.bounded()) continue;
    const AffinePlane s = bounds.attribute({t.corners[0].sw, t.corners[1].sw, t.corners[2].sw});
    const float minX = std::min({t.corners[0].x, t.corners[1].x, t.corners[2].x});
    const float minY = std::min({t.corners[0].y, t.corners[1].y, t.corners[2].y});
    std::uniform_int_distribution<int> pixel(-2, 8);
    for (int p = 0; p < 20; ++p) {
      // Pixels near the lower corner of the box: inside, on the edges and just outside.
      const double cx = std::floor(minX) + pixel(rng) + 0.5, cy = std::floor(minY) + pixel(rng) + 0.5;
      const std::array<Interval, 3> lambda = bounds.barycentrics(cx, cy);
      const Interval z = bounds.depth(cx, cy), value = bounds.ratio(s, cx, cy);
      const Interval stepX = bounds.ratioStep(s, cx, cy, 0), stepY = bounds.ratioStep(s, cx, cy, 1);
      for (int m = 0; m < 16; ++m) {
        Moved moved;
        for (size_t i = 0; i < 3; ++i) {
          // Half the moves at the radius itself, where the bounds are reached.
          const double dx = extreme(rng) ? (move(rng) < 0 ? -kRadius : kRadius) : move(rng);
          const double dy = extreme(rng) ? (move(rng) < 0 ? -kRadius : kRadius) : move(rng);
          moved.x[i] = t.corners[i].x + static_cast<long double>(dx);
          moved.y[i] = t.corners[i].y + static_cast<long double>(dy);
        }
        const auto l = barycentricsOf(moved, cx, cy);
        for (size_t i = 0; i < 3; ++i) ASSERT_TRUE(inside(lambda[i], l[i])) << trial;
        ASSERT_TRUE(inside(z, interpolated(l, t.corners[0].z, t.corners[1].z, t.corners[2].z)));
        const long double here = ratioAt(moved, t, cx, cy);
        ASSERT_TRUE(inside(value, here)) << trial << " " << value.lo << " " << value.hi;
        ASSERT_TRUE(inside(stepX, ratioAt(moved, t, cx + 1, cy) - here)) << trial;
        ASSERT_TRUE(inside(stepY, ratioAt(moved, t, cx, cy + 1) - here)) << trial;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 40000);
}

// A large triangle: the value's bounds are within the first-order width, twice the radius times
// the gradient's 1-norm, and the derivative's relative width is of the order radius / size.
TEST(PerturbedTriangle, LargeTrianglesGetFirstOrderBounds) {
  SetupTriangle t;
  const std::array<std::array<float, 2>, 3> at = {{{10, 10}, {410, 30}, {60, 300}}};
  const std::array<float, 3> oow = {1.0f, 0.25f, 0.5f}, s = {0.0f, 1.0f, 0.5f};
  for (size_t i = 0; i < 3; ++i)
    t.corners[i] = {at[i][0], at[i][1], 0.5f, oow[i], s[i] * oow[i], 0.0f};
  constexpr double kRadius = 1.0 / 16;
  const PerturbedTriangle bounds(t, kRadius);
  ASSERT_TRUE(bounds.bounded());
  const AffinePlane plane = bounds.attribute({t.corners[0].sw, t.corners[1].sw, t.corners[2].sw});
  const double cx = 100.5, cy = 80.5;
  const Interval value = bounds.ratio(plane, cx, cy);
  const Interval dx = bounds.ratioStep(plane, cx, cy, 0), dy = bounds.ratioStep(plane, cx, cy, 1);
  const double gradient = std::fabs((dx.lo + dx.hi) / 2) + std::fabs((dy.lo + dy.hi) / 2);
  EXPECT_LT(value.width(), 2 * kRadius * gradient * 1.05);
  EXPECT_GT(value.width(), 2 * kRadius * gradient * 0.5);  // and not narrower than a move can go
  EXPECT_LT(dx.width() / std::fabs(dx.lo + dx.hi) * 2, 0.02);
  EXPECT_LT(dy.width() / std::fabs(dy.lo + dy.hi) * 2, 0.02);
}

// A block's source box holds every centre's source box as computed, and the bounds over it hold
// the bounds at each centre (what ResultSetBuilder's block classes rely on), for blocks inside,
// across and outside random triangles, near the window's origin and far from it.
TEST(PerturbedTriangle, ABlocksSourceBoxHoldsEachCentresBoxAndBounds) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pixel(-60, 360);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const SetupTriangle t = randomTriangle(rng, trial % 2 ? 200.0 : 12.0);
    const PerturbedTriangle bounds(t, 1.0 / 256);
    if (!bounds.bounded()) continue;
    for (int b = 0; b < 20; ++b) {
      const int bx = pixel(rng) & ~3, by = pixel(rng) & ~3;
      const WindowBox block = bounds.sourceBoxOver(bx + 0.5, by + 0.5, bx + 3.5, by + 3.5);
      const std::array<Interval, 3> blockLambda = bounds.barycentrics(block);
      const Interval blockZ = bounds.depth(block);
      for (int y = by; y < by + 4; ++y)
        for (int x = bx; x < bx + 4; ++x) {
          const WindowBox own = bounds.sourceBox(x + 0.5, y + 0.5);
          ASSERT_LE(block.x.lo, own.x.lo);
          ASSERT_GE(block.x.hi, own.x.hi);
          ASSERT_LE(block.y.lo, own.y.lo);
          ASSERT_GE(block.y.hi, own.y.hi);
          const std::array<Interval, 3> lambda = bounds.barycentrics(own);
          for (size_t i = 0; i < 3; ++i) {
            ASSERT_LE(blockLambda[i].lo, lambda[i].lo);
            ASSERT_GE(blockLambda[i].hi, lambda[i].hi);
          }
          const Interval z = bounds.depth(own);
          ASSERT_LE(blockZ.lo, z.lo);
          ASSERT_GE(blockZ.hi, z.hi);
          ++checked;
        }
    }
  }
  EXPECT_GT(checked, 50000);
}

// What ResultSetBuilder's OwnBlock derives from ratioOver over a block's source box grown by the
// step radius: at every centre p of the block, a moved triangle's s lies within (g_x + g_y) rho
// of the nominal s(p), rho the box's margin around the centres; and within a pixel's own bounds
// (ratioReach), its fine steps within ratioStepReach of the nominal s_x (s_y) at the step's
// middle, from the source boxes of the pixel and of its steps' first centres. Exact arithmetic
// (long double): the float errors are added apart.
TEST(PerturbedTriangle, ABlocksRatioBoundsHoldEveryMovedValueAndStep) {
  std::mt19937 rng(11);
  constexpr double kRadius = 1.0 / 16;
  std::uniform_real_distribution<double> move(-kRadius, kRadius);
  std::uniform_int_distribution<int> pixel(-8, 8);
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const SetupTriangle t = randomTriangle(rng, trial % 3 == 0 ? 10.0 : 150.0);
    const PerturbedTriangle bounds(t, kRadius);
    if (!bounds.bounded()) continue;
    const AffinePlane s = bounds.attribute({t.corners[0].sw, t.corners[1].sw, t.corners[2].sw});
    const AffinePlane& w = bounds.oneOverW();
    const int bx = (static_cast<int>(t.corners[0].x) + pixel(rng)) & ~3;
    const int by = (static_cast<int>(t.corners[0].y) + pixel(rng)) & ~3;
    const double x0 = bx + 0.5, y0 = by + 0.5, x1 = bx + 3.5, y1 = by + 3.5;
    const WindowBox box = bounds.sourceBoxOver(x0, y0, x1, y1);
    const double rho = std::max({x0 - box.x.lo, box.x.hi - x1, y0 - box.y.lo, box.y.hi - y1});
    const double e = std::max(bounds.stepRadius(0), bounds.stepRadius(1));
    const WindowBox around{{box.x.lo - e, box.x.hi + e}, {box.y.lo - e, box.y.hi + e}};
    const PerturbedTriangle::RatioOver r = bounds.ratioOver(s, around, x0, y0, x1, y1);
    if (!r.finite) continue;
    const double g = r.gradient[0] + r.gradient[1];
    const auto nominal = [&](long double x, long double y) {
      return (s.a0 + s.ax * x + s.ay * y) / (w.a0 + w.ax * x + w.ay * y);
    };
    // f_x and f_y of the nominal ratio in closed form.
    const auto slope = [&](long double x, long double y, int axis) {
      const long double d = w.a0 + w.ax * x + w.ay * y;
      const long double n = s.a0 + s.ax * x + s.ay * y;
      return axis == 0 ? (s.ax * d - n * w.ax) / (d * d) : (s.ay * d - n * w.ay) / (d * d);
    };
    // The bounds themselves, at the box's corners and points inside: |f| and its gradient in
    // closed form (perturbed_triangle.h).
    std::uniform_real_distribution<double> u(0, 1);
    for (int q = 0; q < 20; ++q) {
      const long double x =
          q < 4 ? (q & 1 ? around.x.hi : around.x.lo) : around.x.lo + u(rng) * around.x.width();
      const long double y =
          q < 4 ? (q & 2 ? around.y.hi : around.y.lo) : around.y.lo + u(rng) * around.y.width();
      const long double tolerance = 1e-12L;
      ASSERT_LE(std::fabs(nominal(x, y)), r.magnitude * (1 + tolerance));
      ASSERT_LE(std::fabs(slope(x, y, 0)), r.gradient[0] * (1 + tolerance));
      ASSERT_LE(std::fabs(slope(x, y, 1)), r.gradient[1] * (1 + tolerance));
    }
    for (int m = 0; m < 24; ++m) {
      Moved moved;
      for (size_t i = 0; i < 3; ++i) {
        moved.x[i] = t.corners[i].x + static_cast<long double>(move(rng));
        moved.y[i] = t.corners[i].y + static_cast<long double>(move(rng));
      }
      for (int y = by; y < by + 4; ++y)
        for (int x = bx; x < bx + 4; ++x) {
          const double cx = x + 0.5, cy = y + 0.5;
          // Within the scale of the values' magnitude: the long double reference's own rounding.
          const long double tolerance = 1e-12L * (1 + r.magnitude);
          const long double here = ratioAt(moved, t, cx, cy);
          ASSERT_LE(std::fabs(here - nominal(cx, cy)), g * rho + tolerance) << trial;
          const double lx = (x & ~1) + 0.5, ly = (y & ~1) + 0.5;
          const long double stepX = ratioAt(moved, t, lx + 1, cy) - ratioAt(moved, t, lx, cy);
          const long double stepY = ratioAt(moved, t, cx, ly + 1) - ratioAt(moved, t, cx, ly);
          ASSERT_LE(std::fabs(here), r.magnitude + tolerance);
          // A pixel's own bounds, from its and its steps' first centres' source boxes.
          const auto reach = [&](double x, double y) { return bounds.sourceBox(x, y).x.hi - x; };
          ASSERT_LE(std::fabs(here - nominal(cx, cy)),
                    bounds.ratioReach(s, cx, cy, reach(cx, cy)) + tolerance);
          const PerturbedTriangle::StepReach sx =
              bounds.ratioStepReach(s, 0, lx, cy, reach(lx, cy));
          const PerturbedTriangle::StepReach sy =
              bounds.ratioStepReach(s, 1, cx, ly, reach(cx, ly));
          ASSERT_LE(std::fabs(stepX - slope(lx + 0.5, cy, 0)), sx.width + tolerance) << trial;
          ASSERT_LE(std::fabs(stepY - slope(cx, ly + 0.5, 1)), sy.width + tolerance) << trial;
          ASSERT_LE(std::fabs(stepX), sx.slope + tolerance);
          ASSERT_LE(std::fabs(stepY), sy.slope + tolerance);
          ++checked;
        }
    }
  }
  EXPECT_GT(checked, 40000);
}

// Triangles too small for first-order bounds, and degenerate ones, say so.
TEST(PerturbedTriangle, SmallAndDegenerateTrianglesAreNotBounded) {
  SetupTriangle small;
  small.corners[1].x = 0.3f;
  small.corners[2].y = 0.3f;
  EXPECT_FALSE(PerturbedTriangle(small, 1.0 / 16).bounded());
  EXPECT_TRUE(PerturbedTriangle(small, 1.0 / 256).bounded());
  SetupTriangle flat;
  flat.corners[1].x = 5;
  flat.corners[2].x = 10;
  EXPECT_FALSE(PerturbedTriangle(flat, 1.0 / 256).bounded());
}

}  // namespace
}  // namespace vt::reference
