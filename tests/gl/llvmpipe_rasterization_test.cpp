// The oracle's rasterization against Mesa's llvmpipe, bit for bit: which triangle each pixel
// shows, its texture coordinates, their fine derivatives (helper pixels included) and its depth.
// llvmpipe's settings that results depend on are pinned here; the oracle's llvmpipe profile uses
// fused multiply-adds exactly when this CPU has FMA (as llvmpipe does), plain ones otherwise.

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>

#include "build/synthetic_texture.h"
#include "probes/probe_draws.h"
#include "gl/headless_context.h"
#include "reference/renderer.h"
#include "render/arithmetic_points.h"
#include "test_support.h"

namespace vt {
namespace {

class LlvmpipeRasterization : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("LP_NUM_THREADS", "2", 1);
    ::unsetenv("GALLIVM_PERF");
    ::unsetenv("GALLIUM_OVERRIDE_CPU_CAPS");
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 16, .border = 2, .levelCount = 4, .channels = 4}, std::nullopt});
  }
  test::ScratchDirectory dir_;
};

TEST_F(LlvmpipeRasterization, OracleMatchesEveryPixelBitForBit) {
  const HeadlessContext context;
  if (context.renderer().find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "not llvmpipe: " << context.renderer();
  const VirtualTextureReader reader(dir_ / "t.vt");
  const reference::ResidentTexture texture(reader);
  RenderSettings settings;
  settings.debugChannels = true;
  settings.arithmetic = arithmeticPoint(__builtin_cpu_supports("fma") ? "llvmpipe" : "exact");
  settings.viewport = {160, 120};
  for (const unsigned seed : {1u, 2u, 3u}) {
    const ClipSpaceMesh mesh = calibrate::randomTriangles(seed, 120);
    const calibrate::RasterReadback gl = calibrate::drawTriangles(mesh, settings.viewport);
    const Frame oracle = reference::renderFrame(mesh, texture, settings);
    size_t coverage = 0, uv = 0, derivatives = 0, depth = 0, covered = 0;
    for (size_t i = 0; i < oracle.triangle.size(); ++i) {
      const int32_t glTriangle = gl.triangle[i];
      coverage += glTriangle != oracle.triangle[i];
      if (glTriangle < 0 || glTriangle != oracle.triangle[i]) continue;
      ++covered;
      uv += std::bit_cast<uint32_t>(gl.uv[i].x) != std::bit_cast<uint32_t>(oracle.uv[i].x) ||
            std::bit_cast<uint32_t>(gl.uv[i].y) != std::bit_cast<uint32_t>(oracle.uv[i].y);
      for (int c = 0; c < 4; ++c)
        derivatives += std::bit_cast<uint32_t>(gl.derivatives[i][c]) !=
                       std::bit_cast<uint32_t>(oracle.derivatives[i][c]);
      depth += std::bit_cast<uint32_t>(gl.depth[i]) != std::bit_cast<uint32_t>(oracle.depth[i]);
    }
    EXPECT_GT(covered, oracle.triangle.size() / 2) << "seed " << seed;
    EXPECT_EQ(coverage, 0u) << "seed " << seed << ": pixels showing another triangle";
    EXPECT_EQ(uv, 0u) << "seed " << seed << " of " << covered << " covered pixels";
    EXPECT_EQ(derivatives, 0u) << "seed " << seed;
    EXPECT_EQ(depth, 0u) << "seed " << seed;
  }
}

}  // namespace
}  // namespace vt
