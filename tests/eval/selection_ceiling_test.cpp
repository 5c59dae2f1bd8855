// The ceiling of selection (eval/selection_ceiling.h): the windowed SSIM it prices pages with
// is the change of the image's SSIM; its pick is the page of its pool that raises the next
// frame's SSIM most, by what it predicted; an evaluation flies it the same with any number of
// jobs, and only an evaluation flies it.

#include "eval/selection_ceiling.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <random>

#include "build/synthetic_texture.h"
#include "eval/evaluation.h"
#include "eval/image_metrics.h"
#include "reference/recolor.h"
#include "reference/renderer.h"
#include "runtime/virtual_texture_runtime.h"
#include "scene/box_room.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TEST(WindowSsim, GainIsWhatTheChangeAddsToTheSummedSsimOfEveryWindow) {
  constexpr int kWidth = 53, kHeight = 37;
  std::mt19937 random(11);
  std::vector<uint8_t> reference(kWidth * kHeight * 4), image(reference.size());
  for (size_t i = 0; i < reference.size(); ++i) {
    reference[i] = static_cast<uint8_t>(random() % 256);
    image[i] = static_cast<uint8_t>(
        std::clamp<int>(reference[i] + static_cast<int>(random() % 41) - 20, 0, 255));
  }
  WindowSsim windows(kWidth, kHeight);
  EXPECT_EQ(windows.windowCount(), uint64_t{kWidth - 7} * (kHeight - 7));
  windows.reset(reference, image);
  const auto summed = [&](const std::vector<uint8_t>& a) {
    return ssim({kWidth, kHeight, a}, {kWidth, kHeight, reference}) *
           static_cast<double>(windows.windowCount());
  };
  for (int trial = 0; trial < 30; ++trial) {
    // Corners, edges and a pixel listed twice (its last value counts), among random ones.
    std::vector<uint32_t> pixels = {0, kWidth - 1, kWidth * kHeight - 1, kWidth * (kHeight - 1)};
    for (int k = 0; k < 40; ++k) pixels.push_back(random() % (kWidth * kHeight));
    pixels.push_back(pixels[5]);
    std::vector<uint8_t> rgba(pixels.size() * 4);
    for (uint8_t& v : rgba) v = static_cast<uint8_t>(random() % 256);
    std::vector<uint8_t> changed = image;
    for (size_t k = 0; k < pixels.size(); ++k)
      std::copy_n(rgba.begin() + 4 * k, 4, changed.begin() + 4 * pixels[k]);
    const double gain = windows.gain(pixels, rgba);
    // Both sums add about 1,380 windows' Q of order 1 in different orders: 1e-9 is far above
    // their rounding and far below one window's change.
    EXPECT_NEAR(gain, summed(changed) - summed(image), 1e-9) << "trial " << trial;
    if (trial % 3 == 0) {
      windows.apply(pixels, rgba);
      image = changed;
    }
  }
}

struct CeilingScene {
  test::ScratchDirectory dir;
  std::unique_ptr<VirtualTextureReader> reader;
  RenderSettings settings;
  CeilingScene() {
    writeSyntheticTexture(
        dir / "t.vt",
        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
    reader = std::make_unique<VirtualTextureReader>(dir / "t.vt");
    settings.viewport = {96, 64};
    settings.need8 = true;
  }
  Frame view(int frame) const {
    RenderSettings debug = settings;
    debug.debugChannels = true;
    return reference::renderFrame(
        toClipSpace(boxRoom(), boxRoomPath().at(frame), settings.viewport),
        reference::ResidentTexture(*reader), debug);
  }
  // Summed SSIM of `next` under `cache` against its reference.
  double summedSsim(const Frame& next, const CacheState& cache) const {
    std::vector<uint8_t> color;
    reference::recolor(next, cache, settings, color);
    const Viewport v = settings.viewport;
    return ssim({v.width, v.height, color}, {v.width, v.height, next.color}) *
           static_cast<double>(v.width - 7) * static_cast<double>(v.height - 7);
  }
};

TEST(CeilingSelection, PicksThePageOfItsPoolThatRaisesTheNextFrameMostByWhatItPredicted) {
  const CeilingScene scene;
  const Frame now = scene.view(10), next = scene.view(11);
  std::vector<uint64_t> resident;
  for (uint64_t p = 0; p < pageCount(2); ++p) resident.push_back(p);
  const CacheState base = makeCacheState(*scene.reader, resident, 24, 24);
  RuntimeOptions options;
  options.framesX = options.framesY = 24;
  VirtualTextureRuntime runtime(*scene.reader, options);
  runtime.preload(resident);
  FrameStatistics statistics;
  const std::vector<StreamRequest> requests =
      runtime.analyze(now.need, {}, 96, 64, true, 10, statistics);
  ASSERT_GT(requests.size(), 3u);

  CeilingSelection ceiling(*scene.reader, scene.settings, 4096);
  const std::vector<StreamRequest> chosen = ceiling.choose(base, next, requests, 1);
  ASSERT_EQ(ceiling.lastChoice().picked, 1u);
  // The requests follow the pick, once each.
  EXPECT_EQ(chosen.size(),
            requests.size() + 1 -
                std::count_if(requests.begin(), requests.end(),
                              [&](const StreamRequest& r) { return r.page == chosen[0].page; }));

  // Every page of the pool measured alone: the requests' pages and their missing ancestors.
  std::vector<uint64_t> pool;
  for (const StreamRequest& request : requests)
    for (uint32_t level = 3; level <= levelOfAbsoluteIndex(request.page); ++level)
      pool.push_back(absoluteIndex(ancestorAt(fromAbsoluteIndex(request.page), level)));
  std::sort(pool.begin(), pool.end());
  pool.erase(std::unique(pool.begin(), pool.end()), pool.end());
  const double before = scene.summedSsim(next, base);
  uint64_t best = 0;
  double bestGain = -1.0, pickedGain = 0.0;
  for (const uint64_t page : pool) {
    std::vector<uint64_t> with = resident;
    with.push_back(page);
    const double gain =
        scene.summedSsim(next, makeCacheState(*scene.reader, with, 24, 24)) - before;
    if (gain > bestGain) {
      bestGain = gain;
      best = page;
    }
    if (page == chosen[0].page) pickedGain = gain;
  }
  EXPECT_EQ(chosen[0].page, best);
  const double windows = 89.0 * 57.0;
  EXPECT_NEAR(ceiling.lastChoice().predictedGain * windows, pickedGain, 1e-6);
  EXPECT_GT(pickedGain, 0.0);
}

TEST(CeilingSelection, FliesTheSameWithAnyNumberOfJobsAndOnlyInAnEvaluation) {
  const CeilingScene scene;
  FlightConfiguration pixelSum;
  pixelSum.budget = 3;
  FlightConfiguration ceiling = pixelSum;
  ceiling.selection = PageSelection::kCeiling;
  FlightConfiguration nextFrame = pixelSum;
  nextFrame.selection = PageSelection::kCeilingNextFrame;
  std::vector<std::vector<double>> ssims;
  for (const unsigned jobs : {1u, 2u}) {
    EvaluationOptions options;
    options.settings = scene.settings;
    options.jobs = jobs;
    const Evaluation evaluation =
        evaluate(*scene.reader, boxRoom(), boxRoomPath(), {pixelSum, ceiling, nextFrame}, options);
    std::vector<double> values;
    for (const EvaluationRun& run : evaluation.runs)
      for (const FlightFrame& frame : run.result.frames) values.push_back(frame.quality->ssim);
    ssims.push_back(values);
  }
  EXPECT_EQ(ssims[0], ssims[1]);
  FlightOptions options;
  options.settings = scene.settings;
  EXPECT_THAT([&] { fly(*scene.reader, boxRoom(), boxRoomPath(), ceiling, options); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("only vt eval draws")));
  EXPECT_THAT(
      [&] {
        FlightConfiguration::fromJson(nlohmann::json{{"selection", "ceiling"}, {"latency", 2}}, {});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("no 'budget_bytes' or 'latency'")));
  EXPECT_THAT(
      [&] {
        FlightConfiguration::fromJson(nlohmann::json{{"selection", "best"}}, {});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(
          HasSubstr("'selection' must be heuristic, ceiling or ceiling_next_frame")));
  EXPECT_EQ(FlightConfiguration::fromJson(ceiling.toJson(), {}).selection, PageSelection::kCeiling);
}

}  // namespace
}  // namespace vt
