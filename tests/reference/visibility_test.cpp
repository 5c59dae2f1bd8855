#include "reference/visibility.h"

#include <gtest/gtest.h>

#include <bit>
#include <vector>

#include "reference/random_triangles.h"
#include "render/arithmetic_points.h"

namespace vt::reference {
namespace {

TEST(Visibility, CandidatesAreEveryTriangleWhoseGrownBoxHoldsThePixelInDrawOrder) {
  // The result sets' candidates come from the tiles' bins. Random triangles, many reaching past
  // the window and across tiles, on a window that is no multiple of the tile: for every margin
  // the candidates of each pixel must be those a search of every triangle finds, in draw order.
  const ClipSpaceMesh mesh = test::randomTrianglesWithCoplanarCopies(300, 5);
  const Arithmetic arithmetic = arithmeticPoint("llvmpipe");
  const Viewport viewport{101, 67};
  const std::vector<SetupTriangle> triangles = setupTriangles(mesh, viewport, arithmetic);
  ASSERT_GT(triangles.size(), 200u);
  std::vector<int32_t> found, expected;
  size_t listed = 0;
  for (const int margin : {0, 1, 2}) {
    const Visibility visibility(triangles, viewport, DepthFormat::kDepth32F, arithmetic, margin);
    for (int py = 0; py < viewport.height; ++py)
      for (int px = 0; px < viewport.width; ++px) {
        expected.clear();
        for (size_t k = 0; k < triangles.size(); ++k) {
          const SetupTriangle& t = triangles[k];
          if (t.minX - margin <= px && px <= t.maxX + margin && t.minY - margin <= py &&
              py <= t.maxY + margin)
            expected.push_back(static_cast<int32_t>(k));
        }
        visibility.candidates(px, py, found);
        ASSERT_EQ(found, expected) << "pixel " << px << ", " << py << ", margin " << margin;
        listed += found.size();
      }
  }
  EXPECT_GT(listed, 100000u);
}

TEST(Visibility, TheMarginOfTheBinsLeavesTheWinnersAlone) {
  // Bins made with a margin hold more triangles per tile; the winners must be the same bits.
  const ClipSpaceMesh mesh = test::randomTrianglesWithCoplanarCopies(150, 11);
  const Arithmetic arithmetic = arithmeticPoint("llvmpipe");
  const Viewport viewport{101, 67};
  const std::vector<SetupTriangle> triangles = setupTriangles(mesh, viewport, arithmetic);
  const Visibility plain(triangles, viewport, DepthFormat::kDepth24, arithmetic, 0);
  const Visibility grown(triangles, viewport, DepthFormat::kDepth24, arithmetic, 1);
  std::array<PixelHit, Visibility::kTile * Visibility::kTile> a, b;
  size_t covered = 0;
  for (int y0 = 0; y0 < viewport.height; y0 += Visibility::kTile)
    for (int x0 = 0; x0 < viewport.width; x0 += Visibility::kTile) {
      plain.tile(x0, y0, a);
      grown.tile(x0, y0, b);
      for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].triangle, b[i].triangle) << "tile " << x0 << ", " << y0 << ", slot " << i;
        ASSERT_EQ(std::bit_cast<uint32_t>(a[i].depth), std::bit_cast<uint32_t>(b[i].depth));
        ASSERT_EQ(std::bit_cast<uint32_t>(a[i].runnerUpDepth),
                  std::bit_cast<uint32_t>(b[i].runnerUpDepth));
        covered += a[i].triangle >= 0;
      }
    }
  EXPECT_GT(covered, static_cast<size_t>(viewport.width * viewport.height / 2));
}

}  // namespace
}  // namespace vt::reference
