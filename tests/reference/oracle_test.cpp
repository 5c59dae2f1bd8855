// The CPU oracle against first principles: coverage of shared edges, visibility against a brute
// force over every set-up triangle, texture coordinates and derivatives of a screen-filling quad,
// the needbuffer of a known view, and identical bytes for any thread count.

#include <gtest/gtest.h>


#include "build/synthetic_texture.h"
#include "reference/random_triangles.h"
#include "reference/renderer.h"
#include "reference/visibility.h"
#include "render/arithmetic_points.h"
#include "shader/needbuffer.h"
#include "test_support.h"

namespace vt::reference {
namespace {

// Two triangles covering clip space [-1, 1]^2 at w = 1, uv = (x + 1) / 2.
ClipSpaceMesh screenQuad(float z = 0.0f) {
  ClipSpaceMesh mesh;
  for (const auto& [x, y] :
       std::vector<std::pair<float, float>>{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    mesh.vertices.push_back({{x, y, z, 1.0f}, {(x + 1) / 2, (y + 1) / 2}});
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

// A fan of n triangles around a point, sharing edges, covering the whole viewport.
ClipSpaceMesh fan(int n, glm::vec2 centre = {0.123f, -0.271f}) {
  ClipSpaceMesh mesh;
  mesh.vertices.push_back({{centre.x, centre.y, 0.0f, 1.0f}, {0.5f, 0.5f}});
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * 3.14159265358979 * i / n;
    mesh.vertices.push_back(
        {{static_cast<float>(3 * std::cos(a)), static_cast<float>(3 * std::sin(a)), 0.0f, 1.0f},
         {0.5f, 0.5f}});
  }
  for (int i = 0; i < n; ++i)
    mesh.indices.insert(mesh.indices.end(),
                        {0u, static_cast<uint32_t>(1 + i), static_cast<uint32_t>(1 + (i + 1) % n)});
  return mesh;
}

// The winner at a pixel by brute force over all set-up triangles, with the rules of
// visibility.h spelled out again.
int32_t bruteForce(const std::vector<SetupTriangle>& triangles, int px, int py,
                   const Arithmetic& arithmetic) {
  int32_t best = -1;
  float bestZ = 1.0f;
  for (size_t k = 0; k < triangles.size(); ++k) {
    if (!triangles[k].covers(px, py)) continue;
    const float z = windowDepth(triangles[k], px, py, arithmetic);
    if (z < bestZ) {  // strictly less: the earlier drawn keeps a tie
      best = static_cast<int32_t>(k);
      bestZ = z;
    }
  }
  return best;
}

class Oracle : public ::testing::Test {
 protected:
  void SetUp() override {
    // 256 texels at the finest level (P = 16, L = 4), dense.
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 16, .border = 2, .levelCount = 5, .channels = 4}, std::nullopt});
    reader_ = std::make_unique<VirtualTextureReader>(dir_ / "t.vt");
    texture_ = std::make_unique<ResidentTexture>(*reader_);
  }
  test::ScratchDirectory dir_;
  std::unique_ptr<VirtualTextureReader> reader_;
  std::unique_ptr<ResidentTexture> texture_;
};

// The rasterization tests below run for every named point: each point's own coverage (snapped
// edge functions with its grid and tie rule, or softpipe's float spans) and depth, so that the
// llvmpipe and softpipe set-ups have tests of their own on the CPU side, not only crosschecks.
class OracleAtPoint : public Oracle, public ::testing::WithParamInterface<std::string> {
 protected:
  Arithmetic arithmetic() const { return arithmeticPoint(GetParam()); }
};

INSTANTIATE_TEST_SUITE_P(NamedPoints, OracleAtPoint,
                         ::testing::ValuesIn(arithmeticPointNames()),
                         [](const auto& info) { return info.param; });

TEST_P(OracleAtPoint, SharedEdgesCoverEveryPixelExactlyOnce) {
  const Viewport viewport{97, 61};
  // Off-centre fans, and fans around the pixel centre (48.5, 30.5) = NDC (0, 0) whose horizontal
  // and vertical spokes run through rows and columns of pixel centres: the tie rule decides them.
  for (const auto& [n, centre] : std::vector<std::pair<int, glm::vec2>>{
           {3, {0.123f, -0.271f}}, {7, {0.123f, -0.271f}}, {40, {0.123f, -0.271f}},
           {4, {0.0f, 0.0f}}, {8, {0.0f, 0.0f}}, {12, {0.0f, 0.0f}}}) {
    const auto triangles = setupTriangles(fan(n, centre), viewport, arithmetic());
    for (int py = 0; py < viewport.height; ++py)
      for (int px = 0; px < viewport.width; ++px) {
        int count = 0;
        for (const SetupTriangle& t : triangles) count += t.covers(px, py);
        ASSERT_EQ(count, 1) << "fan of " << n << " around (" << centre.x << ", " << centre.y
                            << "), pixel " << px << ", " << py;
      }
  }
}

TEST_P(OracleAtPoint, VisibilityMatchesBruteForceOnRandomTriangles) {
  const ClipSpaceMesh mesh = test::randomTrianglesWithCoplanarCopies(60, 5);
  const Viewport viewport{80, 50};
  const auto triangles = setupTriangles(mesh, viewport, arithmetic());
  const Visibility visibility(triangles, viewport, DepthFormat::kDepth32F, arithmetic());
  for (int py = 0; py < viewport.height; ++py)
    for (int px = 0; px < viewport.width; ++px)
      ASSERT_EQ(visibility.at(px, py).triangle, bruteForce(triangles, px, py, arithmetic()))
          << px << ", " << py;
}

TEST_F(Oracle, ScreenQuadHasExactCoordinatesAndDerivatives) {
  RenderSettings settings;
  settings.debugChannels = true;
  settings.viewport = {256, 256};
  const Frame frame = renderFrame(screenQuad(), *texture_, settings);
  for (int py = 0; py < 256; py += 17)
    for (int px = 0; px < 256; px += 13) {
      const size_t i = static_cast<size_t>(py * 256 + px);
      ASSERT_GE(frame.triangle[i], 0);
      EXPECT_NEAR(frame.uv[i].x, (px + 0.5f) / 256.0f, 1e-6f);
      EXPECT_NEAR(frame.uv[i].y, (py + 0.5f) / 256.0f, 1e-6f);
      EXPECT_NEAR(frame.derivatives[i].x, 1.0f / 256.0f, 1e-7f);
      EXPECT_NEAR(frame.derivatives[i].w, 1.0f / 256.0f, 1e-7f);
      EXPECT_NEAR(frame.derivatives[i].y, 0.0f, 1e-7f);
      // One finest texel per pixel: lod = L = 4, page (px / 16, py / 16) of level 4.
      EXPECT_NEAR(frame.lod[i], 4.0f, 1e-4f);
      EXPECT_EQ(frame.need[i], glm::uvec4(px / 16, py / 16, 4, 1)) << px << ", " << py;
      EXPECT_EQ(frame.depth[i], 0.5f);
    }
}

TEST_F(Oracle, MinifiedQuadNeedsCoarserPagesAndEmptyPixelsAreMarked) {
  // The quad drawn at a quarter of the viewport: 4 texels per pixel, lod = 2.
  ClipSpaceMesh mesh = screenQuad();
  for (ClipVertex& v : mesh.vertices)
    v.position = glm::vec4(v.position.x * 0.25f - 0.5f, v.position.y * 0.25f - 0.5f, 0.0f, 1.0f);
  RenderSettings settings;
  settings.debugChannels = true;
  settings.viewport = {256, 256};
  settings.need8 = true;
  const Frame frame = renderFrame(mesh, *texture_, settings);
  const size_t inside = static_cast<size_t>(70 * 256 + 70),
               outside = static_cast<size_t>(200 * 256 + 200);
  EXPECT_NEAR(frame.lod[inside], 2.0f, 1e-4f);
  EXPECT_EQ(frame.need[inside].z, 2u);
  EXPECT_EQ(frame.need[outside], needClearValue(true));
  EXPECT_EQ(frame.triangle[outside], -1);
  EXPECT_EQ(frame.color[outside * 4 + 3], 0);
}

TEST_F(Oracle, SameBytesForOneTwoAndEightThreads) {
  ClipSpaceMesh mesh = fan(23);
  // Perspective and depth variety: tilt the fan.
  for (ClipVertex& v : mesh.vertices) {
    v.position.w = 1.0f + 0.3f * v.position.x;
    v.position.z = 0.2f * v.position.y;
    v.uv = glm::vec2(0.5f + 0.1f * v.position.x, 0.5f + 0.13f * v.position.y);
  }
  RenderSettings settings;
  settings.debugChannels = true;
  settings.viewport = {123, 77};
  std::vector<Frame> frames;
  // Under gl45 too: the result sets are gathered from the tiles in pixel order.
  applyModel(settings, gl45Model());
  for (const unsigned threads : {1u, 2u, 8u}) {
    settings.threads = threads;
    frames.push_back(renderFrame(mesh, *texture_, settings));
  }
  ASSERT_FALSE(frames[0].sets.empty());
  for (size_t k = 1; k < frames.size(); ++k) {
    EXPECT_EQ(frames[k].color, frames[0].color);
    EXPECT_EQ(frames[k].need, frames[0].need);
    EXPECT_EQ(frames[k].depth, frames[0].depth);
    EXPECT_TRUE(frames[k].sets == frames[0].sets);
  }
}

TEST_F(Oracle, AReusedFrameHoldsExactlyWhatAFreshOneHolds) {
  // A frame that held a full-screen quad, with debug channels and an 8-bit needbuffer, and bytes
  // no render writes: rendered again with a scene that leaves most pixels empty, every channel
  // must equal a fresh frame's, background pixels included.
  RenderSettings first;
  first.debugChannels = true;
  first.need8 = true;
  first.viewport = {123, 77};
  Frame reused = renderFrame(screenQuad(), *texture_, first);
  std::fill(reused.color.begin(), reused.color.end(), uint8_t{0x5a});
  std::fill(reused.residentLevel.begin(), reused.residentLevel.end(), int8_t{7});

  ClipSpaceMesh small = fan(5);
  for (ClipVertex& v : small.vertices) v.position *= glm::vec4(0.2f, 0.2f, 1.0f, 1.0f);
  for (const bool debug : {true, false}) {
    RenderSettings second;
    second.debugChannels = debug;
    applyModel(second, gl45Model());  // the result sets are written too
    second.viewport = first.viewport;
    renderFrame(small, *texture_, second, reused);
    const Frame fresh = renderFrame(small, *texture_, second);
    EXPECT_EQ(reused.color, fresh.color);
    EXPECT_EQ(reused.need, fresh.need);
    EXPECT_EQ(reused.depth, fresh.depth);
    EXPECT_TRUE(reused.sets == fresh.sets);
    EXPECT_EQ(reused.triangle, fresh.triangle);
    EXPECT_EQ(reused.uv, fresh.uv);
    EXPECT_EQ(reused.derivatives, fresh.derivatives);
    EXPECT_EQ(reused.lod, fresh.lod);
    EXPECT_EQ(reused.residentLevel, fresh.residentLevel);
    EXPECT_EQ(reused.residentLevel.size(), debug ? fresh.triangle.size() : 0u);
    EXPECT_GT(std::count(fresh.triangle.begin(), fresh.triangle.end(), -1), 1000);
  }
}

TEST_F(Oracle, TriangleCrossingTheNearPlaneIsClippedNotDropped) {
  ClipSpaceMesh mesh;
  // One vertex behind the eye (w < 0, z < -w): the clipper keeps the visible part.
  mesh.vertices = {{{-0.5f, -0.5f, 0.0f, 1.0f}, {0, 0}},
                   {{0.5f, -0.5f, 0.0f, 1.0f}, {1, 0}},
                   {{0.0f, 2.0f, -3.0f, -1.0f}, {0.5f, 1}}};
  mesh.indices = {0, 1, 2};
  SetupStatistics stats;
  const auto triangles = setupTriangles(mesh, {64, 64}, arithmeticPoint("exact"), &stats);
  EXPECT_EQ(stats.clipped, 1u);
  EXPECT_GE(triangles.size(), 1u);
  RenderSettings settings;
  settings.debugChannels = true;
  settings.viewport = {64, 64};
  const Frame frame = renderFrame(mesh, *texture_, settings);
  const Visibility visibility(triangles, settings.viewport, DepthFormat::kDepth32F,
                              arithmeticPoint("exact"));
  int covered = 0;
  for (int py = 0; py < 64; ++py)
    for (int px = 0; px < 64; ++px) {
      const int32_t expected = bruteForce(triangles, px, py, arithmeticPoint("exact"));
      ASSERT_EQ(visibility.at(px, py).triangle, expected);
      covered += expected >= 0;
      const auto need = frame.need[static_cast<size_t>(py * 64 + px)];
      if (expected >= 0) {
        EXPECT_LE(need.x, (1u << need.z) - 1);  // every page lies inside its level
        EXPECT_LE(need.y, (1u << need.z) - 1);
      }
    }
  EXPECT_GT(covered, 0);
}

}  // namespace
}  // namespace vt::reference
