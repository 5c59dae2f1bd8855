// Recolouring a drawn frame under another cache state (reference/recolor.h) gives the bytes of
// drawing it under that state: for either arithmetic, with and without trilinear filtering, with
// float filtering and with the sampler's, for caches holding coarse levels only or a random
// sample of pages, and for any thread count.

#include "reference/recolor.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "build/synthetic_texture.h"
#include "render/arithmetic_points.h"
#include "scene/box_room.h"
#include "scene/camera_path.h"
#include "test_support.h"

namespace vt::reference {
namespace {

class Recolor : public ::testing::Test {
 protected:
  void SetUp() override {
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
    reader_ = std::make_unique<VirtualTextureReader>(dir_ / "t.vt");
  }

  // Levels 0-2; a random third of the finer stored pages (the root is added when missing); the
  // same third in another order, so in other frames; and levels 0-2 again, reversed.
  std::vector<CacheState> caches() const {
    std::vector<CacheState> states{cacheOfLevels(*reader_, 2, 4096)};
    std::mt19937 random(7);
    std::vector<uint64_t> pages;
    for (uint64_t p = 0; p < pageCount(reader_->description().finestLevel()); ++p)
      if (reader_->contains(fromAbsoluteIndex(p)) && random() % 3 == 0) pages.push_back(p);
    states.push_back(makeCacheState(*reader_, pages, 24, 24));
    std::shuffle(pages.begin(), pages.end(), random);
    states.push_back(makeCacheState(*reader_, pages, 24, 24));
    std::vector<uint64_t> coarse(pageCount(2));
    for (uint64_t p = 0; p < coarse.size(); ++p) coarse[p] = coarse.size() - 1 - p;
    states.push_back(makeCacheState(*reader_, coarse, 24, 24));
    return states;
  }

  test::ScratchDirectory dir_;
  std::unique_ptr<VirtualTextureReader> reader_;
};

TEST_F(Recolor, GivesTheBytesOfDrawingUnderTheCacheState) {
  const ResidentTexture everything(*reader_);
  const std::vector<CacheState> states = caches();
  const CameraPath path = boxRoomPath();
  int differing = 0, compared = 0;
  for (const char* point : {"exact", "llvmpipe"})
    for (const bool trilinear : {true, false})
      for (const bool exactFilter : {true, false})
        for (const int frame : {0, path.frameCount() / 2}) {
          RenderSettings settings;
          settings.viewport = {83, 61};  // odd sizes: quads cut by the edges
          settings.arithmetic = arithmeticPoint(point);
          settings.trilinear = trilinear;
          settings.exactFilter = exactFilter;
          settings.threads = frame == 0 ? 1 : 3;
          const ClipSpaceMesh mesh = toClipSpace(boxRoom(), path.at(frame), settings.viewport);
          RenderSettings debug = settings;
          debug.debugChannels = true;
          const Frame drawn = renderFrame(mesh, everything, debug);
          // All states at once, where pixels that read alike are shaded once for several.
          std::vector<const CacheState*> all;
          std::vector<std::vector<uint8_t>> together(states.size());
          std::vector<std::vector<uint8_t>*> outputs;
          for (size_t k = 0; k < states.size(); ++k) {
            all.push_back(&states[k]);
            outputs.push_back(&together[k]);
          }
          recolor(drawn, all, settings, outputs);
          for (size_t k = 0; k < states.size(); ++k) {
            const CacheState& cache = states[k];
            const Frame direct = renderFrame(mesh, cache, settings);
            std::vector<uint8_t> color;
            recolor(drawn, cache, settings, color);
            ASSERT_EQ(color.size(), direct.color.size());
            EXPECT_EQ(color, direct.color) << "arithmetic " << point << " trilinear " << trilinear
                                           << " exact filter " << exactFilter;
            EXPECT_EQ(together[k], direct.color) << "together, state " << k;
            // The caches differ from every page resident: the test compares colours that move.
            differing += drawn.color != direct.color;
            ++compared;
          }
        }
  EXPECT_EQ(differing, compared);
}

// A LookAhead camera's pass reads no texel; its needbuffer, depth and triangles are the full
// pass's.
TEST_F(Recolor, ANeedOnlyPassGivesTheNeedbufferAndDepthOfTheFullPass) {
  const std::vector<CacheState> states = caches();
  for (const bool need8 : {false, true})
    for (const int frame : {0, 7}) {
      RenderSettings settings;
      settings.viewport = {83, 61};
      settings.need8 = need8;
      settings.needScaleLog2 = frame == 7 ? 1 : 0;
      const ClipSpaceMesh mesh = toClipSpace(boxRoom(), boxRoomPath().at(frame), settings.viewport);
      const Frame full = renderFrame(mesh, states.back(), settings);
      RenderSettings needOnly = settings;
      needOnly.needOnly = true;
      const Frame only = renderFrame(mesh, states.back(), needOnly);
      EXPECT_EQ(only.need, full.need);
      EXPECT_EQ(only.depth, full.depth);
      EXPECT_EQ(only.triangle, full.triangle);
      EXPECT_EQ(std::count(only.color.begin(), only.color.end(), 0), std::ssize(only.color));
      EXPECT_NE(std::count(full.color.begin(), full.color.end(), 0), std::ssize(full.color));
    }
}

// Shading a list of pixels gives recolor()'s bytes at those pixels, pixels without geometry and
// repeated ones included; and the pages each pixel reads are those its indirection lookups name:
// removing every page but the root and those pages' ancestors leaves its colour as it was.
TEST_F(Recolor, ListedPixelsGetRecolorsBytesAndReadOnlyThePagesNamed) {
  const ResidentTexture everything(*reader_);
  const std::vector<CacheState> states = caches();
  for (const bool trilinear : {true, false}) {
    RenderSettings settings;
    settings.viewport = {83, 61};
    settings.trilinear = trilinear;
    const ClipSpaceMesh mesh = toClipSpace(boxRoom(), boxRoomPath().at(3), settings.viewport);
    RenderSettings debug = settings;
    debug.debugChannels = true;
    Frame drawn = renderFrame(mesh, everything, debug);
    // The room fills the screen: a few pixels are marked as showing no geometry.
    for (size_t i = 0; i < drawn.triangle.size(); i += 29) drawn.triangle[i] = -1;
    std::vector<uint32_t> pixels;
    for (uint32_t i = 0; i < drawn.triangle.size(); i += 7) pixels.push_back(i);
    pixels.push_back(pixels.front());
    for (const CacheState& cache : states) {
      std::vector<uint8_t> whole;
      recolor(drawn, cache, settings, whole);
      std::vector<uint8_t> listed(pixels.size() * 4);
      recolorPixels(drawn, cache, settings, pixels, listed);
      for (size_t k = 0; k < pixels.size(); ++k)
        ASSERT_TRUE(std::equal(listed.begin() + 4 * k, listed.begin() + 4 * k + 4,
                               whole.begin() + 4 * pixels[k]))
            << "pixel " << pixels[k] << " trilinear " << trilinear;
    }
    const std::vector<PagesRead> reads = pagesRead(drawn, reader_->description(), settings);
    ASSERT_EQ(reads.size(), drawn.triangle.size());
    int checked = 0;
    for (uint32_t i = 0; i < reads.size(); i += 97) {
      EXPECT_EQ(reads[i].covered, drawn.triangle[i] >= 0);
      if (!reads[i].covered) continue;
      const bool finest = reads[i].first.level == reader_->description().finestLevel();
      EXPECT_EQ(reads[i].first == reads[i].second, !trilinear || finest);
      std::vector<uint64_t> kept;
      for (const PageId read : {reads[i].first, reads[i].second})
        for (uint32_t level = 0; level <= read.level; ++level)
          kept.push_back(absoluteIndex(ancestorAt(read, level)));
      std::sort(kept.begin(), kept.end());
      kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
      // The same frames for the pages kept, every other stored page after them in the second.
      std::vector<uint64_t> all = kept;
      for (uint64_t p = 0; p < pageCount(reader_->description().finestLevel()); ++p)
        if (reader_->contains(fromAbsoluteIndex(p)) &&
            !std::binary_search(kept.begin(), kept.end(), p))
          all.push_back(p);
      const uint32_t pixel[] = {i};
      std::vector<uint8_t> alone(4), among(4);
      recolorPixels(drawn, makeCacheState(*reader_, kept, 37, 37), settings, pixel, alone);
      recolorPixels(drawn, makeCacheState(*reader_, all, 37, 37), settings, pixel, among);
      EXPECT_EQ(alone, among) << "pixel " << i;
      ++checked;
    }
    EXPECT_GT(checked, 5);
  }
}

TEST_F(Recolor, RefusesAFrameWithoutDebugChannels) {
  RenderSettings settings;
  settings.viewport = {16, 16};
  const ClipSpaceMesh mesh = toClipSpace(boxRoom(), boxRoomPath().at(0), settings.viewport);
  const Frame plain = renderFrame(mesh, ResidentTexture(*reader_), settings);
  std::vector<uint8_t> color;
  EXPECT_THAT([&] { recolor(plain, caches().front(), settings, color); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  ::testing::HasSubstr("recolor: the frame was not drawn with debug channels")));
}

}  // namespace
}  // namespace vt::reference
