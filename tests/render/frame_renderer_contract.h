#pragma once
// What every FrameRenderer must do (render/frame_renderer.h), as checks that each backend's tests
// run over its own renderers: tests/render/frame_renderer_test.cpp (the oracle) and
// tests/gl/gl_frame_renderer_test.cpp (the GL path, on whatever driver runs the tests).

#include <gtest/gtest.h>

#include <functional>
#include <memory>

#include "build/synthetic_texture.h"
#include "render/frame_renderer.h"
#include "scene/box_room.h"
#include "scene/camera_path.h"
#include "test_support.h"

namespace vt::test {

using MakeRenderer = std::function<std::unique_ptr<FrameRenderer>(const CacheState&)>;

// A small synthetic texture seen along the box room's path.
class ContractScene {
 public:
  ContractScene() {
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 32, .border = 2, .levelCount = 5, .channels = 4}, std::nullopt});
    reader_ = std::make_unique<VirtualTextureReader>(dir_ / "t.vt");
    settings.viewport = {48, 32};
  }

  const VirtualTextureReader& reader() const { return *reader_; }
  ClipSpaceMesh view(int frame) const {
    return toClipSpace(boxRoom(), boxRoomPath().at(frame), settings.viewport);
  }

  RenderSettings settings;

 private:
  ScratchDirectory dir_;
  std::unique_ptr<VirtualTextureReader> reader_;
};

// renderDelayed hands out the needbuffer and depth that a synchronous draw of the previous frame
// reads, with this frame's colour; the first call hands out none.
inline void expectDelayedReadbackOneFrameLate(const MakeRenderer& make,
                                              const ContractScene& scene) {
  const CacheState cache = cacheOfLevels(scene.reader(), 2, 4096);
  const std::unique_ptr<FrameRenderer> delayed = make(cache), synchronous = make(cache);
  const Frame first = delayed->renderDelayed(scene.view(0), scene.settings, /*readDepth=*/true);
  EXPECT_TRUE(first.need.empty());
  EXPECT_TRUE(first.depth.empty());
  for (int frame = 1; frame < 4; ++frame) {
    const Frame got = delayed->renderDelayed(scene.view(frame), scene.settings, true);
    const Frame previous = synchronous->render(scene.view(frame - 1), scene.settings, true);
    const Frame current = synchronous->render(scene.view(frame), scene.settings);
    ASSERT_NE(previous.need, current.need) << "the camera moves: frames differ";
    EXPECT_EQ(got.need, previous.need) << "frame " << frame;
    EXPECT_EQ(got.depth, previous.depth) << "frame " << frame;
    EXPECT_EQ(got.color, current.color) << "frame " << frame;
  }
}

// Colour and needbuffer of every pixel; depth exactly when asked; a needbuffer-only pass gives
// the same needbuffer.
inline void expectReadsBackWhatIsAsked(const MakeRenderer& make, const ContractScene& scene) {
  const CacheState cache = cacheOfLevels(scene.reader(), -1, 4096);
  const std::unique_ptr<FrameRenderer> renderer = make(cache);
  const Frame full = renderer->render(scene.view(0), scene.settings, /*readDepth=*/true);
  const size_t pixels =
      static_cast<size_t>(scene.settings.viewport.width) * scene.settings.viewport.height;
  EXPECT_EQ(full.color.size(), pixels * 4);
  EXPECT_EQ(full.need.size(), pixels);
  EXPECT_EQ(full.depth.size(), pixels);
  RenderSettings needOnly = scene.settings;
  needOnly.needOnly = true;
  const Frame need = renderer->render(scene.view(0), needOnly);
  EXPECT_TRUE(need.depth.empty());
  EXPECT_EQ(need.need, full.need);
}

// After cacheChanged(), a draw shows the changed cache state.
inline void expectDrawsTheChangedCacheState(const MakeRenderer& make, const ContractScene& scene) {
  CacheState cache = rootOnlyCache(scene.reader().description());  // every texel zero
  const std::unique_ptr<FrameRenderer> renderer = make(cache);
  const Frame before = renderer->render(scene.view(0), scene.settings);
  storePage(cache, 0, 0, scene.reader().readStoredPage(PageId{}));  // the root's own texels
  renderer->cacheChanged();
  EXPECT_NE(renderer->render(scene.view(0), scene.settings).color, before.color);
}

}  // namespace vt::test
