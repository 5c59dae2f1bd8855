// The GL path's needbuffer readback, synchronous against asynchronous (pixel-buffer objects and a
// fence, GlFrameRenderer::renderDelayed), in one process: the heightmap terrain (scene/terrain.h)
// at 1920 x 1080 with every stored level up to an 8192^2 cache, each frame drawn and its 32-bit
// needbuffer brought to the CPU, the camera moving. Prints the time per frame of each and the
// ratio async / sync. The price of asynchronous readback, the needbuffer one frame late, is
// measured by `vt fly --readback async` (docs/streaming.md).
//   usage: readback_benchmark [frames]

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "build/synthetic_texture.h"
#include "gl/gl_frame_renderer.h"
#include "gl/headless_context.h"
#include "scene/terrain.h"

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::max(2, std::atoi(argv[1])) : 60;
  ::setenv("LP_NUM_THREADS", "2", 0);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("vt-readback-benchmark-" + std::to_string(::getpid()) + ".vt");
  vt::writeSyntheticTexture(
      file, {{.pageSize = 128, .border = 4, .levelCount = 7, .channels = 4}, std::nullopt});
  {
    const vt::VirtualTextureReader reader(file);
    const vt::HeadlessContext context;
    const vt::CacheState cache = vt::cacheOfLevels(reader, -1, 8192);
    vt::GlFrameRenderer renderer(cache);
    const vt::TerrainShape shape;
    const vt::Mesh mesh = vt::heightmapTerrain(shape);
    vt::RenderSettings settings;
    settings.viewport = {1920, 1080};
    const auto clipAt = [&](int frame) {
      vt::Camera camera = vt::terrainCamera(shape);
      const glm::vec3 step(0.0f, 0.0f, -0.5f * static_cast<float>(frame));
      camera.position += step;
      camera.target += step;
      return vt::toClipSpace(mesh, camera, settings.viewport);
    };
    const auto time = [&](auto&& frameFunction) {
      const auto start = std::chrono::steady_clock::now();
      size_t covered = 0;
      for (int f = 0; f < frames; ++f) covered += frameFunction(f);
      const double ms =
          1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return std::pair(ms / frames, covered);
    };
    const auto countCovered = [](const std::vector<glm::uvec4>& need) {
      return static_cast<size_t>(
          std::count_if(need.begin(), need.end(), [](const glm::uvec4& v) { return v.w != 0; }));
    };
    renderer.render(clipAt(0), settings);  // warm up: shader compilation, allocations
    const auto [syncMs, syncCovered] =
        time([&](int f) { return countCovered(renderer.render(clipAt(f), settings).need); });
    // The delayed readback brings the needbuffer only; the colour stays in the target.
    vt::RenderSettings delayedSettings = settings;
    delayedSettings.needOnly = true;
    const auto [asyncMs, asyncCovered] = time([&](int f) {
      return countCovered(renderer.renderDelayed(clipAt(f), delayedSettings).need);
    });
    std::printf("%s, 1920 x 1080, %d frames, LP_NUM_THREADS=%s\n", context.renderer().c_str(),
                frames, std::getenv("LP_NUM_THREADS"));
    std::printf("synchronous readback:  %.2f ms per frame (%zu covered pixels read)\n", syncMs,
                syncCovered);
    std::printf(
        "asynchronous readback: %.2f ms per frame (%zu covered pixels read, a frame late)\n",
        asyncMs, asyncCovered);
    std::printf("async / sync: %.3fx the time per frame\n", asyncMs / syncMs);
  }
  std::filesystem::remove(file);
  return 0;
}
