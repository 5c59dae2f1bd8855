// The whole virtual-texture fragment shader against Mesa's llvmpipe, bit for bit: the GL program
// (the shared logic included verbatim) and the oracle render the same scene from the same cache
// state, some pages resident and the rest falling back to ancestors; colour and needbuffer must
// agree on every pixel, for exact and hardware bilinear filtering, with and without trilinear
// blending, in both needbuffer encodings.

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>
#include <fstream>
#include <random>

#include "build/synthetic_texture.h"
#include "gl/gl_frame_renderer.h"
#include "gl/headless_context.h"
#include "random_triangles.h"
#include "reference/renderer.h"
#include "render/arithmetic_points.h"
#include "resident_pages.h"
#include "test_support.h"

namespace vt {
namespace {

// Textured triangles at many scales and angles: magnified, minified, grazing, some clipped.
ClipSpaceMesh texturedScene(unsigned seed) {
  std::mt19937 random(seed);
  ClipSpaceMesh mesh;
  test::appendRandomTriangles(mesh, random, 80);
  // s and t exactly 0 and 1 at the corners of a screen-filling background quad drawn last.
  const uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
  for (const auto& [x, y] :
       std::vector<std::pair<float, float>>{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    mesh.vertices.push_back({{x, y, 0.99f, 1.0f}, {(x + 1) / 2, (y + 1) / 2}});
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  return mesh;
}

struct Mode {
  bool exactFilter, trilinear, need8;
  int needScaleLog2 = 0;  // a reduced needbuffer's LOD compensation (runtime/needbuffer_scale.h)
};

class LlvmpipeShading : public ::testing::TestWithParam<Mode> {};

TEST_P(LlvmpipeShading, OracleMatchesColourAndNeedbufferBitForBit) {
  ::setenv("LP_NUM_THREADS", "2", 1);
  const HeadlessContext context;
  if (context.renderer().find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "not llvmpipe: " << context.renderer();
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 16, .border = 2, .levelCount = 5, .channels = 4}, std::nullopt});
  const VirtualTextureReader reader(dir / "t.vt");
  // Levels 0..2 resident, every other page of level 3, a few of level 4: the rest falls back.
  const std::vector<uint64_t> resident = test::pagesFallingBack(2, {2, 7});
  const CacheState cache = makeCacheState(reader, resident, 12, 8);

  RenderSettings settings;
  settings.viewport = {192, 128};
  settings.arithmetic = arithmeticPoint(__builtin_cpu_supports("fma") ? "llvmpipe" : "exact");
  settings.exactFilter = GetParam().exactFilter;
  settings.trilinear = GetParam().trilinear;
  settings.need8 = GetParam().need8;
  settings.needScaleLog2 = GetParam().needScaleLog2;
  GlFrameRenderer renderer(cache);
  for (const unsigned seed : {11u, 12u}) {
    const ClipSpaceMesh mesh = texturedScene(seed);
    const Frame gl = renderer.render(mesh, settings, /*readDepth=*/true);
    const Frame oracle = reference::renderFrame(mesh, cache, settings);
    size_t colour = 0, need = 0, maxDifference = 0, covered = 0, depth = 0;
    ASSERT_EQ(gl.depth.size(), oracle.depth.size());
    for (size_t i = 0; i < oracle.need.size(); ++i) {
      covered += oracle.triangle[i] >= 0;
      depth += std::bit_cast<uint32_t>(gl.depth[i]) != std::bit_cast<uint32_t>(oracle.depth[i]);
      need += gl.need[i] != oracle.need[i];
      for (size_t c = 0; c < 4; ++c) {
        const int difference = std::abs(int{gl.color[i * 4 + c]} - int{oracle.color[i * 4 + c]});
        colour += difference != 0;
        maxDifference = std::max(maxDifference, static_cast<size_t>(difference));
      }
    }
    EXPECT_EQ(covered, oracle.need.size()) << "the background quad covers every pixel";
    EXPECT_EQ(need, 0u) << "seed " << seed;
    EXPECT_EQ(depth, 0u) << "seed " << seed << ": the depth the Distance heuristic reads back";
    EXPECT_EQ(colour, 0u) << "seed " << seed << ", largest difference " << maxDifference;
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, LlvmpipeShading,
                         ::testing::Values(Mode{true, true, false}, Mode{true, false, true},
                                           Mode{false, true, false}, Mode{false, false, true},
                                           Mode{true, true, false, 2}, Mode{false, false, true, 3}),
                         [](const auto& info) {
                           return std::string(info.param.exactFilter ? "TexelFetch"
                                                                     : "HardwareLinear") +
                                  (info.param.trilinear ? "Trilinear" : "Bilinear") +
                                  (info.param.need8 ? "Need8" : "Need32") +
                                  (info.param.needScaleLog2
                                       ? "Reduced" + std::to_string(1 << info.param.needScaleLog2)
                                       : "");
                         });

}  // namespace
}  // namespace vt
