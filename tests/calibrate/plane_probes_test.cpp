// The plane group of the probe pack (calibrate/plane_probes.h) without a GL context: its
// triangles lie where it says (window positions on the 1/256 grid, window depths floats, the same
// through a fused and an unfused viewport transform), its squares' depths can tell the Z24
// members apart, and the shift evidence finds a change of one value or one pixel in a shifted
// copy. On llvmpipe the group is drawn and fitted in tests/gl/vt_capture_test.cpp.

#include "calibrate/plane_probes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace vt::calibrate {
namespace {

using ::testing::HasSubstr;

// The window value of a clip coordinate, fused and unfused (render/arithmetic.h, viewport).
std::pair<float, float> window(float clip, float w, float half) {
  const float ndc = clip / w;
  return {std::fma(ndc, half, half), ndc * half + half};
}

TEST(PlaneProbes, TrianglesAtWOneLieOnTheGridWithFloatDepthsEitherWay) {
  const std::vector<PlaneProbe> probes = planeProbes();
  ASSERT_EQ(probes.size(), 15u);
  EXPECT_EQ(probes.back().format, DepthFormat::kDepth24);
  size_t checked = 0;
  for (const PlaneProbe& probe : probes) {
    if (probe.format != DepthFormat::kDepth32F) continue;
    SCOPED_TRACE(probe.name);
    ASSERT_EQ(probe.mesh.indices.size(), 3 * probe.copies.size());
    for (const ClipVertex& v : probe.mesh.vertices) {
      if (v.position.w != 1.0f) continue;  // "w 0.5, 2, 3": the vertex depth's computation
      const auto [xFused, xUnfused] = window(v.position.x, 1, probe.viewport.width / 2.0f);
      const auto [yFused, yUnfused] = window(v.position.y, 1, probe.viewport.height / 2.0f);
      const auto [zFused, zUnfused] = window(v.position.z, 1, 0.5f);
      EXPECT_EQ(xFused, xUnfused);
      EXPECT_EQ(yFused, yUnfused);
      EXPECT_EQ(zFused, zUnfused);
      EXPECT_EQ(std::ldexp(xFused, 8), std::floor(std::ldexp(xFused, 8)));
      EXPECT_EQ(std::ldexp(yFused, 8), std::floor(std::ldexp(yFused, 8)));
      EXPECT_EQ(std::ldexp(double{zFused}, 24), std::floor(std::ldexp(double{zFused}, 24)));
      EXPECT_GE(xFused, 0.0f);
      EXPECT_LT(xFused, static_cast<float>(probe.viewport.width));
      EXPECT_LT(yFused, static_cast<float>(probe.viewport.height));
      EXPECT_GT(zFused, 0.0f);
      EXPECT_LT(zFused, 1.0f);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3u * (1 + 6 + 5 + 5 + 2 + 2));
}

TEST(PlaneProbes, TheSquaresDepthsTellTheZ24MembersApart) {
  const PlaneProbe squares = planeProbes().back();
  ASSERT_EQ(squares.mesh.vertices.size(), 4096u * 6);
  size_t nearTies = 0, membersDiffer = 0;
  for (size_t q = 0; q < 4096; ++q) {
    const ClipVertex& first = squares.mesh.vertices[6 * q];
    for (size_t v = 1; v < 6; ++v)
      EXPECT_EQ(squares.mesh.vertices[6 * q + v].position.z, first.position.z);
    const auto [fused, unfused] = window(first.position.z, first.position.w, 0.5f);
    ASSERT_EQ(fused, unfused);
    ASSERT_GE(fused, 0.25f);
    ASSERT_LT(fused, 1.0f);
    // Every fourth square lies at the float nearest a tie (k + 1/2) / (2^24 - 1).
    const double below = std::floor(double{fused} * 16777215.0);
    nearTies += q % 4 == 0 && (static_cast<float>((below + 0.5) / 16777215.0) == fused ||
                               static_cast<float>((below - 0.5) / 16777215.0) == fused);
    // The oracle's two members (reference/visibility.cpp, depthKey).
    const float product = fused * 16777215.0f;
    membersDiffer += std::nearbyint(product) != std::trunc(product);
  }
  EXPECT_EQ(nearTies, 1024u);
  // Floats come no nearer a tie than their spacing allows, so the members differ only where the
  // product rounds onto one: on 306 squares of this draw.
  EXPECT_GE(membersDiffer, 256u);
}

// A readback of `viewport` with triangle `id` drawn over the pixels of a small right triangle at
// `at`, its values made from the pixel's offset from `at` (as an evaluation that moves with the
// triangle would give).
void drawMoving(RasterReadback& r, Viewport viewport, glm::ivec2 at, int32_t id) {
  const size_t pixels = static_cast<size_t>(viewport.width) * viewport.height;
  if (r.triangle.empty()) {
    r.triangle.assign(pixels, -1);
    r.uv.assign(pixels, glm::vec2(0));
    r.derivatives.assign(pixels, glm::vec4(0));
    r.depth.assign(pixels, 1.0f);
  }
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20 - y; ++x) {
      const size_t p = static_cast<size_t>(at.y + y) * viewport.width + at.x + x;
      r.triangle[p] = id;
      r.uv[p] = glm::vec2(0.1f + 0.01f * x, 0.3f + 0.007f * y);
      r.derivatives[p] = glm::vec4(0.01f, 0, 0, 0.007f);
      r.depth[p] = 0.5f + 0.001f * x;
    }
}

// Readbacks of the group as an implementation whose planes move with the triangle would draw them.
std::vector<RasterReadback> movingReadbacks(const std::vector<PlaneProbe>& probes) {
  std::vector<RasterReadback> drawn(probes.size());
  for (size_t d = 0; d < probes.size(); ++d)
    for (size_t c = 0; c < probes[d].copies.size(); ++c)
      drawMoving(drawn[d], probes[d].viewport, glm::ivec2(4) + probes[d].copies[c],
                 static_cast<int32_t>(c));
  return drawn;
}

TEST(PlaneProbes, ShiftEvidenceFindsOneChangedValueOrPixel) {
  const std::vector<PlaneProbe> probes = planeProbes();
  std::vector<RasterReadback> drawn = movingReadbacks(probes);
  // Shifts 1 to 32 against the base (6 copies) and four copies along x and along y: 14 copies of
  // 210 pixels.
  ShiftEvidence e = shiftEvidence(probes, drawn);
  EXPECT_EQ(e.pixels, 14u * 210u);
  EXPECT_EQ(e.differing, 0u);
  EXPECT_EQ(e.smallestShift, 0);
  EXPECT_THAT(shiftFinding(e), HasSubstr("keeps its values bit for bit"));

  // One depth of the copy shifted by 4 one float off.
  const size_t shift4 = 3;
  ASSERT_EQ(probes[shift4].name, "shift 4");
  const size_t p = static_cast<size_t>(4 + 4 + 2) * probes[shift4].viewport.width + 4 + 4 + 3;
  ASSERT_EQ(drawn[shift4].triangle[p], 0);
  drawn[shift4].depth[p] = std::nextafter(drawn[shift4].depth[p], 2.0f);
  e = shiftEvidence(probes, drawn);
  EXPECT_EQ(e.differing, 1u);
  EXPECT_EQ(e.smallestShift, 4);
  EXPECT_THAT(shiftFinding(e), HasSubstr("change from a shift of 4"));
  EXPECT_THAT(shiftFinding(e), HasSubstr("1 of 2940 differ"));

  // One pixel of the copy 256 along y not drawn: counted from the base's side.
  drawn = movingReadbacks(probes);
  const size_t yCopies = 8;
  ASSERT_EQ(probes[yCopies].name, "y copies");
  const size_t q = static_cast<size_t>(4 + 256) * probes[yCopies].viewport.width + 4;
  ASSERT_EQ(drawn[yCopies].triangle[q], 3);
  drawn[yCopies].triangle[q] = -1;
  e = shiftEvidence(probes, drawn);
  EXPECT_EQ(e.pixels, 14u * 210u - 1 + 1);
  EXPECT_EQ(e.differing, 1u);
  EXPECT_EQ(e.smallestShift, 256);
}

// The noperspective group: the oracle draws the divided mesh in place of the drawn one, which
// holds only where dividing by w is exact (either way an implementation divides) and the divided
// vertices land on the 1/256 grid with float window depths.
TEST(PlaneProbes, NoperspectiveTrianglesDivideByTheirWExactly) {
  const std::vector<NoperspectiveProbe> probes = noperspectiveProbes();
  ASSERT_EQ(probes.size(), 2u);
  EXPECT_EQ(probes[0].drawn.indices.size(), 3u * 400u);
  EXPECT_EQ(probes[1].drawn.indices.size(), 3u * 60u);
  std::set<float> ws;
  for (const NoperspectiveProbe& probe : probes) {
    SCOPED_TRACE(probe.name);
    ASSERT_EQ(probe.drawn.vertices.size(), probe.divided.vertices.size());
    EXPECT_EQ(probe.drawn.indices, probe.divided.indices);
    for (size_t i = 0; i < probe.drawn.vertices.size(); ++i) {
      const ClipVertex &v = probe.drawn.vertices[i], &d = probe.divided.vertices[i];
      const float w = v.position.w;
      ws.insert(w);
      ASSERT_EQ(d.position.w, 1.0f);
      EXPECT_EQ(d.uv, v.uv);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(v.position[k] / w, d.position[k]);
        EXPECT_EQ(v.position[k] * (1.0f / w), d.position[k]);
      }
      const auto [xFused, xUnfused] = window(d.position.x, 1, probe.viewport.width / 2.0f);
      const auto [yFused, yUnfused] = window(d.position.y, 1, probe.viewport.height / 2.0f);
      const auto [zFused, zUnfused] = window(d.position.z, 1, 0.5f);
      EXPECT_EQ(xFused, xUnfused);
      EXPECT_EQ(zFused, zUnfused);
      EXPECT_EQ(xFused * 256.0f, std::floor(xFused * 256.0f));
      EXPECT_EQ(yFused * 256.0f, std::floor(yFused * 256.0f));
      EXPECT_TRUE(xFused >= 0 && xFused < 256 && yFused >= 0 && yFused < 256);
      EXPECT_TRUE(zFused >= 0.25f && zFused < 0.75f);
      EXPECT_EQ(zFused * 0x1p24f, std::floor(zFused * 0x1p24f));
    }
  }
  EXPECT_EQ(ws, (std::set<float>{0.5f, 1.0f, 2.0f, 4.0f}));
}

}  // namespace
}  // namespace vt::calibrate
