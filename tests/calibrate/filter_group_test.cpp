// The filter group of the probe pack (calibrate/filter_fit.h, drawFilterProbesAtCacheSizes)
// without a GL context, through a drawer that answers every draw: it asks for its five draws as
// one group, and its block textures join the fit only where their decoding is pinned, with their
// texels decoded block by block as that decoding says. On llvmpipe the group is drawn and fitted
// in tests/gl/vt_capture_test.cpp.

#include <gtest/gtest.h>

#include "calibrate/filter_fit.h"

namespace vt::calibrate {
namespace {

// Answers every shader draw with zeros and counts the group sizes asked for.
class AnsweringDrawer : public ProbeDrawer {
 public:
  std::vector<glm::vec4> shader(const ShaderProbe& probe) override {
    ++shaderDraws;
    return std::vector<glm::vec4>(probe.inputs.size(), glm::vec4(0));
  }
  std::vector<glm::u8vec4> colour(const ShaderProbe&) override { return {}; }
  RasterReadback triangles(const ClipSpaceMesh&, Viewport, DepthFormat, Interpolation) override {
    return {};
  }
  ProbeIdentity identity() override { return {}; }
  bool holdsGroup(size_t draws) override {
    groups.push_back(draws);
    return held;
  }
  int shaderDraws = 0;
  std::vector<size_t> groups;
  bool held = true;
};

TEST(FilterGroup, BlockTexturesJoinTheFitOnlyWhereTheirDecodingIsPinned) {
  const BlockDecoding decoding{.colour = PaletteRule::kTruncated, .alpha = PaletteRule::kTruncated};
  for (const auto& [colour, alpha, joined] :
       {std::tuple{false, false, 3u}, {true, false, 4u}, {true, true, 5u}}) {
    SCOPED_TRACE(std::to_string(colour) + std::to_string(alpha));
    AnsweringDrawer drawer;
    const UsingProbeDrawer using_(drawer);
    std::vector<FilterSample> samples;
    ASSERT_TRUE(drawFilterProbesAtCacheSizes(samples, {decoding, colour, alpha}));
    EXPECT_EQ(drawer.groups, std::vector<size_t>{5});
    EXPECT_EQ(drawer.shaderDraws, 5);  // every draw of the group, counted or not
    ASSERT_EQ(samples.size(), joined);
    for (const FilterSample& s : samples) {
      EXPECT_EQ(s.out.size(), 8192u);
      EXPECT_EQ(s.probe.texels.size(),
                static_cast<size_t>(s.probe.textureSize.x) * s.probe.textureSize.y);
    }
    if (joined < 4) continue;
    // The BC1 texture's texels are its blocks decoded: the block at (5, 1) of 1,024 x 2.
    const FilterSample& bc1 = samples[3];
    ASSERT_EQ(bc1.probe.blockFormat, PixelFormat::kBc1);
    ASSERT_EQ(bc1.probe.textureSize, glm::ivec2(4096, 8));
    const std::array<BlockTexel, 16> texels =
        decodeBlock(PixelFormat::kBc1, bc1.probe.blocks.data() + (1 * 1024 + 5) * 8, decoding);
    for (int k = 0; k < 16; ++k) {
      const glm::u8vec4 t = bc1.probe.texels[static_cast<size_t>((4 + k / 4) * 4096 + 20 + k % 4)];
      const BlockTexel& want = texels[static_cast<size_t>(k)];
      EXPECT_EQ(t, glm::u8vec4(want[0], want[1], want[2], want[3])) << k;
    }
  }
}

TEST(FilterGroup, AFolderWithoutTheGroupAddsNothing) {
  AnsweringDrawer drawer;
  drawer.held = false;
  const UsingProbeDrawer using_(drawer);
  std::vector<FilterSample> samples;
  EXPECT_FALSE(drawFilterProbesAtCacheSizes(samples, {}));
  EXPECT_TRUE(samples.empty());
  EXPECT_EQ(drawer.shaderDraws, 0);
}

}  // namespace
}  // namespace vt::calibrate
