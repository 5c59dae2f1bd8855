// The oracle's result sets under gl45 against an implementation that snaps the vertices elsewhere:
// the same mesh with every vertex moved in window space by up to the model's snapping (2^-4
// pixel), drawn by the oracle with llvmpipe's arithmetic (one gl45 allows), lies in the sets of
// the unmoved mesh at every pixel. The scene is a subdivided ground plane under perspective (every
// LOD, fractional, most pixels inside one triangle of their 4 x 4 block: the sets built from a
// block's widths, ResultSetBuilder's OwnBlock) and triangles in front of it (edges, occlusion),
// textured with detail from a cache where pages fall back to their ancestors.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <span>

#include "build/synthetic_texture.h"
#include "reference/api/api_internal.h"
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

TEST_F(ResultSets, JudgingAFrameBuildsTheSetsOfExactlyThePixelsWhereItDiffers) {
  const ClipSpaceMesh mesh = groundAndTriangles();
  RenderSettings bounded;
  bounded.viewport = kViewport;
  applyModel(bounded, gl45Model());
  RenderSettings pinned = bounded;
  applyModel(pinned, llvmpipeModel());
  const Frame every = renderFrame(mesh, *cache_, bounded);
  const Frame other = renderFrame(snappedElsewhere(mesh, 0.9 / 16, 1), *cache_, pinned);
  const std::vector<uint32_t> otherNeed = oracle::flatNeed(other.need);  // as judged takes it
  RenderSettings judging = bounded;
  judging.judged = {other.color, otherNeed};
  for (const unsigned threads : {1u, 2u, 3u}) {
    judging.threads = threads;
    const Frame judged = renderFrame(mesh, *cache_, judging);
    EXPECT_EQ(judged.color, every.color);
    EXPECT_EQ(judged.need, every.need);
    ASSERT_TRUE(judged.sets.judged);
    ASSERT_EQ(judged.sets.offsets.size(), every.sets.offsets.size());
    uint64_t built = 0;
    for (size_t i = 0; i < every.need.size(); ++i) {
      const bool identical =
          other.need[i] == every.need[i] &&
          std::equal(other.color.begin() + static_cast<std::ptrdiff_t>(4 * i),
                     other.color.begin() + static_cast<std::ptrdiff_t>(4 * i + 4),
                     every.color.begin() + static_cast<std::ptrdiff_t>(4 * i));
      ASSERT_EQ(judged.sets.built(i), !identical) << "pixel " << i << ", " << threads << " threads";
      if (identical) continue;
      ++built;
      // The same alternatives as every pixel's sets hold there.
      ASSERT_TRUE(std::equal(judged.sets.alternatives.begin() + judged.sets.offsets[i],
                             judged.sets.alternatives.begin() + judged.sets.offsets[i + 1],
                             every.sets.alternatives.begin() + every.sets.offsets[i],
                             every.sets.alternatives.begin() + every.sets.offsets[i + 1]))
          << "pixel " << i << ", " << threads << " threads";
    }
    // The same verdict, from the differing pixels' sets alone.
    const FrameComparison a = compareFrames(every, other.color, other.need, false);
    const FrameComparison b = compareFrames(judged, other.color, other.need, false);
    EXPECT_GT(built, 100u);
    EXPECT_EQ(built, a.explained + a.unexplained);
    EXPECT_EQ(b.identical, a.identical);
    EXPECT_EQ(b.explained, a.explained);
    EXPECT_EQ(b.unexplained, a.unexplained);
    EXPECT_EQ(b.explainedBy, a.explainedBy);
    EXPECT_EQ(b.classificationImage.size(), a.classificationImage.size());
  }
  // Another frame, differing where the judged one was identical, has no set there: refused.
  const Frame judged = renderFrame(mesh, *cache_, judging);
  std::vector<uint8_t> changed = other.color;
  size_t pixel = 0;
  while (judged.sets.built(pixel)) ++pixel;
  changed[4 * pixel] ^= 1;
  EXPECT_THAT([&] { compareFrames(judged, changed, other.need, false); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  ::testing::HasSubstr("the result sets were built against another frame (pixel " +
                                       std::to_string(pixel) + " differs")));
  // A judged frame of another size is refused before anything is drawn.
  judging.judged.color = std::span(other.color).first(8);
  EXPECT_THAT([&] { renderFrame(mesh, *cache_, judging); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  ::testing::HasSubstr("the judged frame is not of the viewport's size")));
}

}  // namespace
}  // namespace vt::reference
