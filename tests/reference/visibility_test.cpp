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
  // holds each triangle once, with its pixels). Random
  // triangles, many reaching past the window, on a window that is no multiple of the block: for
  // every margin each pixel's candidates must be those a search of every triangle finds, in draw
  // order, both ways.
  const ClipSpaceMesh mesh = test::randomTrianglesWithCoplanarCopies(300, 5);
  const Arithmetic arithmetic = arithmeticPoint("llvmpipe");
  const Viewport viewport{101, 67};
  const std::vector<SetupTriangle> triangles = setupTriangles(mesh, viewport, arithmetic);
  ASSERT_GT(triangles.size(), 200u);
  std::vector<int32_t> found, expected;
  Visibility::BlockCandidates block;
  size_t listed = 0;
  for (const int margin : {0, 1, 2}) {
    const Visibility visibility(triangles, viewport, DepthFormat::kDepth32F, arithmetic, margin);
    for (int y0 = 0; y0 < viewport.height; y0 += Visibility::kBlock)
      for (int x0 = 0; x0 < viewport.width; x0 += Visibility::kBlock) {
        visibility.blockCandidates(x0, y0, block);
        for (int k = 0; k < Visibility::kBlock * Visibility::kBlock; ++k) {
          const int px = x0 + k % Visibility::kBlock, py = y0 + k / Visibility::kBlock;
          expected.clear();
          if (px < viewport.width && py < viewport.height)
            for (size_t i = 0; i < triangles.size(); ++i) {
              const SetupTriangle& t = triangles[i];
              if (t.minX - margin <= px && px <= t.maxX + margin && t.minY - margin <= py &&
                  py <= t.maxY + margin)
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
