// The oracle keeps the FrameRenderer contract (frame_renderer_contract.h), and a renderer of every
// page draws straight from the file only where the cache state lacks pages.

#include "render/frame_renderer.h"

#include <gtest/gtest.h>

#include "reference/renderer.h"
#include "backends/backend.h"
#include "render/frame_renderer_contract.h"

namespace vt {
namespace {

std::unique_ptr<FrameRenderer> oracle(const CacheState& cache) {
  return makeFrameRenderer(Backend::kOracle, cache);
}

TEST(OracleFrameRenderer, HandsOutTheNeedbufferAndDepthOneFrameLateUnderDelayedReadback) {
  test::expectDelayedReadbackOneFrameLate(oracle, test::ContractScene());
}

TEST(OracleFrameRenderer, ReadsBackWhatIsAsked) {
  test::expectReadsBackWhatIsAsked(oracle, test::ContractScene());
}

TEST(OracleFrameRenderer, DrawsTheChangedCacheState) {
  test::expectDrawsTheChangedCacheState(oracle, test::ContractScene());
}

TEST(OracleFrameRenderer, DrawsEveryPageFromTheFileOnlyWhereTheCacheLacksSome) {
  const test::ContractScene scene;
  const VirtualTextureReader& reader = scene.reader();
  const CacheState all = cacheOfLevels(reader, -1, 4096), coarse = cacheOfLevels(reader, 1, 4096);
  ASSERT_EQ(all.residentPages.size(), reader.storedPageCount());
  ASSERT_LT(coarse.residentPages.size(), reader.storedPageCount());
  EXPECT_EQ(makeFrameRendererOfEveryPage(Backend::kOracle, reader, all)->cache(), &all);
  const std::unique_ptr<FrameRenderer> file =
      makeFrameRendererOfEveryPage(Backend::kOracle, reader, coarse);
  EXPECT_EQ(file->cache(), nullptr);
  EXPECT_EQ(
      file->render(scene.view(0), scene.settings).color,
      reference::renderFrame(scene.view(0), reference::ResidentTexture(reader), scene.settings)
          .color);
}

}  // namespace
}  // namespace vt
