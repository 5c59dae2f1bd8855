// Reduced needbuffers (runtime/needbuffer_scale.h): error against run time. The box room's
// default camera path at 1280 x 720 on a 16384^2 texture (P = 128); for the needbuffer at full
// resolution and at 1/2, 1/4 and 1/8 per axis (jittered per frame), per frame:
//   - run time: drawing the needbuffer with the oracle plus analysing it;
//   - page recall: the share of the full-resolution frame's needed pages that the reduced one
//     requests, in the frame alone and over its last four frames (the jitter moves the samples);
//   - pixel recall: the share of covered full-resolution pixels whose page is requested.
// Prints the means and each scale's time as a ratio of the full resolution's, in one process.

#include <chrono>
#include <cstdio>
#include <deque>
#include <set>

#include "reference/renderer.h"
#include "render/cache_state.h"
#include "runtime/needbuffer_analysis.h"
#include "runtime/needbuffer_scale.h"
#include "scene/box_room.h"
#include "scene/camera_path.h"
#include "shader/needbuffer.h"

namespace {

using Clock = std::chrono::steady_clock;

std::vector<uint64_t> neededPages(const std::vector<glm::uvec4>& need) {
  return vt::neededPages(need, false).pages;
}

}  // namespace

int main() {
  vt::TextureDescription description;
  description.pageSize = 128;
  description.border = 4;
  description.channels = 4;
  description.levelCount = 8;  // 16384^2 texels
  const vt::CacheState cache = vt::rootOnlyCache(description);
  const vt::Mesh mesh = vt::boxRoom();
  const vt::CameraPath path = vt::boxRoomPath();
  const vt::Viewport screen{1280, 720};

  struct Result {
    double seconds = 0.0, pageRecall = 0.0, pageRecall4 = 0.0, pixelRecall = 0.0,
           pixelRecall4 = 0.0;
  };
  Result results[4];
  std::vector<std::vector<glm::uvec4>> full;  // the full-resolution needbuffers, frame by frame
  for (int k = 0; k <= 3; ++k) {
    std::deque<std::vector<uint64_t>> recent;
    vt::RenderSettings settings;
    settings.viewport = vt::reducedViewport(screen, k);
    settings.needScaleLog2 = k;
    for (int frame = 0; frame < path.frameCount(); ++frame) {
      const auto start = Clock::now();
      const vt::ClipSpaceMesh clip =
          vt::toClipSpace(mesh, path.at(frame), settings.viewport, vt::needJitter(frame, k));
      const vt::Frame drawn = vt::reference::renderFrame(clip, cache, settings);
      const vt::NeedBufferAnalysis analysis = vt::analyzeNeedBuffer(
          drawn.need, {}, settings.viewport.width, settings.viewport.height, {});
      results[k].seconds += std::chrono::duration<double>(Clock::now() - start).count();
      if (k == 0) full.push_back(drawn.need);

      // Errors against the full-resolution needbuffer of the same frame.
      recent.push_back(neededPages(drawn.need));
      if (recent.size() > 4) recent.pop_front();
      std::set<uint64_t> now(recent.back().begin(), recent.back().end()), lastFour;
      for (const auto& pages : recent) lastFour.insert(pages.begin(), pages.end());
      const std::vector<uint64_t> wanted = neededPages(full[static_cast<size_t>(frame)]);
      size_t found = 0, found4 = 0, pixels = 0, pixelsFound = 0, pixelsFound4 = 0;
      for (const uint64_t page : wanted) found += now.count(page), found4 += lastFour.count(page);
      for (const glm::uvec4& value : full[static_cast<size_t>(frame)])
        if (const auto page = vt::decodeNeed(value, false)) {
          ++pixels;
          pixelsFound += now.count(vt::absoluteIndex(*page));
          pixelsFound4 += lastFour.count(vt::absoluteIndex(*page));
        }
      results[k].pageRecall += double(found) / double(std::max<size_t>(1, wanted.size()));
      results[k].pageRecall4 += double(found4) / double(std::max<size_t>(1, wanted.size()));
      results[k].pixelRecall += double(pixelsFound) / double(std::max<size_t>(1, pixels));
      results[k].pixelRecall4 += double(pixelsFound4) / double(std::max<size_t>(1, pixels));
      (void)analysis;
    }
  }
  const double frames = path.frameCount();
  std::printf("needbuffer scale on the box room path, %d frames at %d x %d, 16384^2 texture\n",
              path.frameCount(), screen.width, screen.height);
  std::printf("%-6s %12s %10s %12s %14s %12s %14s\n", "scale", "ms/frame", "time", "page recall",
              "page recall 4", "pixel recall", "pixel recall 4");
  for (int k = 0; k <= 3; ++k) {
    const Result& r = results[k];
    std::printf("1/%-4d %12.2f %9.3fx %11.1f%% %13.1f%% %11.2f%% %13.2f%%\n", 1 << k,
                1000.0 * r.seconds / frames, r.seconds / results[0].seconds,
                100.0 * r.pageRecall / frames, 100.0 * r.pageRecall4 / frames,
                100.0 * r.pixelRecall / frames, 100.0 * r.pixelRecall4 / frames);
  }
  return 0;
}
