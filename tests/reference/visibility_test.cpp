#include "reference/visibility.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "reference/random_triangles.h"
#include "render/arithmetic_points.h"

namespace vt::reference {
namespace {

TEST(Visibility, CandidatesAreEveryTriangleWhoseGrownBoxHoldsThePixelInDrawOrder) {
  // The result sets' candidates come from Embree, one ray per pixel or one packet per 4 x 4
  // block, its reports kept where the triangle's own grown box holds the pixel (a block's list
  // holds each triangle once, with its pixels), or from the tiles' bins of the grown boxes
  // (CandidateSearch::kBins). Random triangles, many reaching past the window, on a window that
  // is no multiple of the block, some with a clipped corner's candidate margin (one of them wider
  // than the window): for every margin each pixel's candidates must be those a search of every
  // triangle finds, in draw order, every way.
  const ClipSpaceMesh mesh = test::randomTrianglesWithCoplanarCopies(300, 5);
  const Arithmetic arithmetic = arithmeticPoint("llvmpipe");
  const Viewport viewport{101, 67};
  std::vector<SetupTriangle> triangles = setupTriangles(mesh, viewport, arithmetic);
  ASSERT_GT(triangles.size(), 200u);
  for (size_t i = 0; i < triangles.size(); i += 7) triangles[i].candidateMargin = 3;
  triangles[53].candidateMargin = 1000;
  std::vector<int32_t> found, expected;
  Visibility::BlockCandidates block, binned;
  size_t listed = 0;
  for (const int margin : {0, 1, 2}) {
    const Visibility visibility(triangles, viewport, DepthFormat::kDepth32F, arithmetic, margin);
    const Visibility bins(triangles, viewport, DepthFormat::kDepth32F, arithmetic, margin,
                          Visibility::CandidateSearch::kBins);
    for (int y0 = 0; y0 < viewport.height; y0 += Visibility::kBlock)
      for (int x0 = 0; x0 < viewport.width; x0 += Visibility::kBlock) {
        visibility.blockCandidates(x0, y0, block);
        bins.blockCandidates(x0, y0, binned);
        ASSERT_EQ(binned.triangles, block.triangles) << "block " << x0 << ", " << y0;
        ASSERT_EQ(binned.pixels, block.pixels) << "block " << x0 << ", " << y0;
        for (int k = 0; k < Visibility::kBlock * Visibility::kBlock; ++k) {
          const int px = x0 + k % Visibility::kBlock, py = y0 + k / Visibility::kBlock;
          expected.clear();
          if (px < viewport.width && py < viewport.height)
            for (size_t i = 0; i < triangles.size(); ++i) {
              const SetupTriangle& t = triangles[i];
              const int m = margin + t.candidateMargin;
              if (t.minX - m <= px && px <= t.maxX + m && t.minY - m <= py && py <= t.maxY + m)
                expected.push_back(static_cast<int32_t>(i));
            }
          block.of(k % Visibility::kBlock, k / Visibility::kBlock, found);
          ASSERT_EQ(found, expected)
              << "pixel " << px << ", " << py << ", margin " << margin;
          if (px < viewport.width && py < viewport.height) {
            visibility.candidates(px, py, found);
            ASSERT_EQ(found, expected) << "pixel " << px << ", " << py << ", margin " << margin;
          }
          listed += expected.size();
        }
        ASSERT_TRUE(std::is_sorted(block.triangles.begin(), block.triangles.end()));
        ASSERT_EQ(std::adjacent_find(block.triangles.begin(), block.triangles.end()),
                  block.triangles.end());
      }
  }
  EXPECT_GT(listed, 100000u);
}

}  // namespace
}  // namespace vt::reference
