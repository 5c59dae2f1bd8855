// The oracle's result sets under gl45 against an implementation that snaps the vertices elsewhere:
// the same mesh with every vertex moved in window space by up to the model's snapping (2^-4
// pixel), drawn by the oracle with llvmpipe's arithmetic (one gl45 allows), lies in the sets of
// the unmoved mesh at every pixel. The scene is a subdivided ground plane under perspective (every
// LOD, fractional, most pixels inside one triangle of their 4 x 4 block: the sets built from a
// block's widths, ResultSetBuilder's OwnBlock) and triangles in front of it (edges, occlusion),
// textured with detail from a cache where pages fall back to their ancestors.

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "build/synthetic_texture.h"
#include "reference/renderer.h"
#include "render/arithmetic_points.h"
#include "render/frame_comparison.h"
#include "resident_pages.h"
#include "test_support.h"

namespace vt::reference {
namespace {

constexpr Viewport kViewport{192, 128};

// A ground plane of n x n quads from near (w = 1) to far (w = 12), every vertex in front of the
// camera and inside the depth range (nothing is clipped), and a few triangles above it.
ClipSpaceMesh groundAndTriangles() {
  ClipSpaceMesh mesh;
  constexpr int kCells = 12;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      const float u = static_cast<float>(i) / kCells, v = static_cast<float>(j) / kCells;
      const float w = 1.0f + 11.0f * v;
      // World x across, height -1 under the eye, distance w: clip (x, y, z) scaled by w.
      const float x = (2.0f * u - 1.0f) * 1.3f * w, y = -1.0f + 1.9f * v * w / w;
      mesh.vertices.push_back({{x, y * w * 0.999f, (0.2f + 0.7f * v) * w, w}, {u, v}});
    }
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const auto a = static_cast<uint32_t>(j * (kCells + 1) + i), b = a + 1, c = a + kCells + 1,
                 d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  std::mt19937 random(5);
  std::uniform_real_distribution<float> coordinate(-0.9f, 0.9f), uv(0.0f, 1.0f), w(1.0f, 3.0f);
  for (int k = 0; k < 6; ++k)
    for (int corner = 0; corner < 3; ++corner) {
      const float vw = w(random);
      mesh.vertices.push_back({{coordinate(random) * vw, coordinate(random) * vw, -0.5f * vw, vw},
                               {uv(random), uv(random)}});
      mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
    }
  return mesh;
}

// Every vertex moved by up to `pixels` in window x and y (a clip-space move of pixels * 2 w / W).
ClipSpaceMesh snappedElsewhere(ClipSpaceMesh mesh, double pixels, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> by(-pixels, pixels);
  for (ClipVertex& v : mesh.vertices) {
    v.position.x += static_cast<float>(by(random) * 2 * v.position.w / kViewport.width);
    v.position.y += static_cast<float>(by(random) * 2 * v.position.w / kViewport.height);
  }
  return mesh;
}

class ResultSets : public ::testing::Test {
 protected:
  void SetUp() override {
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 16, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
    reader_ = std::make_unique<VirtualTextureReader>(dir_ / "t.vt");
    // Levels 0..3 resident, every third page of level 4 and every fifth of level 5: the rest
    // falls back to ancestors.
    const std::vector<uint64_t> resident = test::pagesFallingBack(3, {3, 5});
    cache_ = std::make_unique<CacheState>(makeCacheState(*reader_, resident, 24, 24));
  }

  test::ScratchDirectory dir_;
  std::unique_ptr<VirtualTextureReader> reader_;
  std::unique_ptr<CacheState> cache_;
};

TEST_F(ResultSets, UnderGl45AMeshWhoseVerticesSnapElsewhereLiesInTheSets) {
  const ClipSpaceMesh mesh = groundAndTriangles();
  for (const bool texelFetch : {true, false}) {
    RenderSettings bounded;
    bounded.viewport = kViewport;
    applyModel(bounded, gl45Model());
    bounded.exactFilter = texelFetch;
    bounded.need8 = !texelFetch;
    RenderSettings pinned = bounded;
    applyModel(pinned, llvmpipeModel());
    const Frame nominal = renderFrame(mesh, *cache_, bounded);
    ASSERT_FALSE(nominal.sets.empty());
    uint64_t differ = 0;
    for (unsigned seed = 1; seed <= 6; ++seed) {
      // 0.9 of 2^-4 pixel: the float clip coordinates' own rounding stays inside the snapping.
      const Frame other = renderFrame(snappedElsewhere(mesh, 0.9 / 16, seed), *cache_, pinned);
      const FrameComparison c = compareFrames(nominal, other.color, other.need, bounded.need8);
      EXPECT_EQ(c.unexplained, 0u)
          << (texelFetch ? "texel fetches" : "GL_LINEAR") << ", seed " << seed;
      differ += c.explained;
    }
    // The moves change what is drawn (else the check had no power).
    EXPECT_GT(differ, 1000u) << (texelFetch ? "texel fetches" : "GL_LINEAR");
  }
}

}  // namespace
}  // namespace vt::reference
