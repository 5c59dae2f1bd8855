// The plane-positions member (render/arithmetic.h, PlanePositions): the planes through the window
// positions snapped to the coverage's grid, worked out by hand on a right triangle whose float
// corners lie 2^-10 pixel off the 1/256 grid.

#include <gtest/gtest.h>

#include "reference/triangle_setup.h"
#include "render/arithmetic_points.h"

namespace vt::reference {
namespace {

// Window corners (2.5 + 2^-10, 2.5), (10.5 + 2^-10, 2.5) and (2.5, 10.5 - 2^-10) in a 16 x 16
// viewport (x_ndc = X / 8 - 1, exact), w = 1, (s, t) = (0, 0), (1, 0), (0, 1) and window z 0.5,
// 0.75, 0.25. On the 8-bit grid, half to even, they snap to (2.5, 2.5), (10.5, 2.5), (2.5, 10.5):
// (X - 0.5) 256 is 512.25, 2560.25 and 2559.75.
SetupTriangle setUp(PlanePositions positions) {
  const float off = 0x1p-10f;
  const auto vertex = [](float x, float y, float z, glm::vec2 uv) {
    return ClipVertex{{x / 8 - 1, y / 8 - 1, 2 * z - 1, 1}, uv};
  };
  ClipSpaceMesh mesh;
  mesh.vertices = {vertex(2.5f + off, 2.5f, 0.5f, {0, 0}), vertex(10.5f + off, 2.5f, 0.75f, {1, 0}),
                   vertex(2.5f, 10.5f - off, 0.25f, {0, 1})};
  mesh.indices = {0, 1, 2};
  Arithmetic arithmetic = arithmeticPoint("exact");
  arithmetic.coverage.subpixelBits = 8;
  arithmetic.coverage.rounding = SnapRounding::kHalfEven;
  arithmetic.planePositions = positions;
  const std::vector<SetupTriangle> triangles = setupTriangles(mesh, {16, 16}, arithmetic);
  EXPECT_EQ(triangles.size(), 1u);
  return triangles.empty() ? SetupTriangle{} : triangles[0];
}

TEST(PlanePositions, SnappedPlanesGoThroughTheGridPointsAsWorkedOutByHand) {
  const SetupTriangle t = setUp(PlanePositions::kSnapped);
  // Through (2.5, 2.5), (10.5, 2.5), (2.5, 10.5): s = (X - 2.5) / 8, t = (Y - 2.5) / 8 and
  // z = 0.5 + (X - 2.5) / 32 - (Y - 2.5) / 32; at the centre of pixel (0, 0), (0.5, 0.5):
  // s = t = -0.25, z = 0.5. Every step of the float setup is exact here (powers of two).
  EXPECT_EQ(t.s.a0, -0.25f);
  EXPECT_EQ(t.s.dadx, 0.125f);
  EXPECT_EQ(t.s.dady, 0.0f);
  EXPECT_EQ(t.t.a0, -0.25f);
  EXPECT_EQ(t.t.dadx, 0.0f);
  EXPECT_EQ(t.t.dady, 0.125f);
  EXPECT_EQ(t.z.a0, 0.5f);
  EXPECT_EQ(t.z.dadx, 0.03125f);
  EXPECT_EQ(t.z.dady, -0.03125f);
  EXPECT_EQ(t.oneOverW.a0, 1.0f);
  EXPECT_EQ(t.oneOverW.dadx, 0.0f);
  // The corners the result sets move stay the float positions (the snapped ones lie within the
  // model's snapping radius of them).
  float largestX = 0;
  for (const WindowCorner& c : t.corners) largestX = std::max(largestX, c.x);
  EXPECT_EQ(largestX, 10.5f + 0x1p-10f);
}

TEST(PlanePositions, UnsnappedPlanesGoThroughTheFloatPositions) {
  const SetupTriangle t = setUp(PlanePositions::kUnsnapped);
  // The corners 2^-10 off the grid tilt the planes: s is 0 along the leg from (2.5 + 2^-10, 2.5)
  // to (2.5, 10.5 - 2^-10), at x = 2.5 + 2^-10 - (y - 2.5) 2^-10 / (8 - 2^-10), so s grows with y
  // by 2^-10 / (8 - 2^-10) / 8 (about 2^-16), and at (0.5, 0.5), where the leg lies at about
  // 2.5 + 1.25 2^-10, s is about -0.25 - 1.25 2^-13.
  // (In float: the setup cancels two products of about 1/8, so 2^-23 of those, 1e-8.)
  EXPECT_NEAR(t.s.dady, 0x1p-10 / (8 - 0x1p-10) / 8, 1e-8);
  EXPECT_NEAR(t.s.a0, -0.25 - 1.25 * 0x1p-13, 1e-7);
  EXPECT_NE(t.s.a0, -0.25f);
}

}  // namespace
}  // namespace vt::reference
