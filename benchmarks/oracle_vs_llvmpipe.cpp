// Frames per second of the CPU oracle against Mesa's llvmpipe drawing the same scene with the GL
// renderer's own shader (the shared virtual-texture logic), in the same process: a generated
// terrain of 20,000 triangles at 1280x720 from a cache state holding every page. Prints the time
// of each, the ratio oracle / llvmpipe (target <= 1.0) and the oracle's scaling from 1 to 2
// threads (target >= 1.8). llvmpipe runs with LP_NUM_THREADS=2.
//   usage: oracle_vs_llvmpipe [frames]

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "build/synthetic_texture.h"
#include "gl/gl_frame_renderer.h"
#include "gl/headless_context.h"
#include "reference/renderer.h"
#include "render/arithmetic_points.h"
#include "scene/camera.h"

namespace {

// A 100 x 100 quad height field (20,000 triangles) over [-50, 50]^2, uv over [0, 1]^2.
vt::Mesh terrain() {
  vt::Mesh mesh;
  constexpr int kCells = 100;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      const float x = static_cast<float>(i) - 50.0f, z = static_cast<float>(j) - 50.0f;
      mesh.positions.emplace_back(x, 2.0f * std::sin(x * 0.21f) * std::cos(z * 0.17f), z);
      mesh.uvs.emplace_back(static_cast<float>(i) / kCells, static_cast<float>(j) / kCells);
    }
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const uint32_t a = static_cast<uint32_t>(j * (kCells + 1) + i), b = a + 1, c = a + kCells + 1,
                     d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  return mesh;
}

template <class Draw>
double medianMilliseconds(int frames, Draw draw) {
  std::vector<double> times;
  for (int k = 0; k < frames; ++k) {
    const auto start = std::chrono::steady_clock::now();
    draw();
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  ::setenv("LP_NUM_THREADS", "2", 1);
  const auto file = std::filesystem::temp_directory_path() /
                    ("vt-oracle-bench-" + std::to_string(::getpid()) + ".vt");
  vt::writeSyntheticTexture(
      file, {{.pageSize = 128, .border = 4, .levelCount = 5, .channels = 4}, std::nullopt});
  const vt::VirtualTextureReader reader(file);
  std::vector<uint64_t> pages(reader.storedPageCount());
  for (uint64_t p = 0; p < pages.size(); ++p) pages[p] = p;
  const vt::CacheState cache = vt::makeCacheState(reader, pages, 19, 19);

  vt::Camera camera;
  camera.position = {0, 18, 45};
  camera.target = {0, 0, 0};
  vt::RenderSettings settings;
  settings.viewport = {1280, 720};
  settings.arithmetic = vt::arithmeticPoint("llvmpipe");
  const vt::ClipSpaceMesh mesh = vt::toClipSpace(terrain(), camera, settings.viewport);

  const vt::HeadlessContext context;
  vt::GlFrameRenderer gl(cache);
  gl.draw(mesh, settings);  // compile and warm up
  const double llvmpipe = medianMilliseconds(frames, [&] { gl.draw(mesh, settings); });
  // Like the GL renderer's targets, the oracle's frame is reused from frame to frame.
  vt::Frame frame;
  settings.threads = 2;
  vt::reference::renderFrame(mesh, cache, settings, frame);
  const double oracle2 =
      medianMilliseconds(frames, [&] { vt::reference::renderFrame(mesh, cache, settings, frame); });
  settings.threads = 1;
  const double oracle1 =
      medianMilliseconds(frames, [&] { vt::reference::renderFrame(mesh, cache, settings, frame); });
  std::filesystem::remove(file);

  std::printf(
      "scene: generated terrain, %zu triangles, 1280x720, every page resident, trilinear, texel "
      "fetches\n",
      mesh.indices.size() / 3);
  std::printf("%s (%s), LP_NUM_THREADS=2: %.1f ms per frame\n", context.renderer().c_str(),
              context.version().c_str(), llvmpipe);
  std::printf("oracle, 2 threads: %.1f ms per frame; 1 thread: %.1f ms\n", oracle2, oracle1);
  std::printf("oracle / llvmpipe: %.2fx the time per frame (target <= 1.0)\n", oracle2 / llvmpipe);
  std::printf("oracle scaling 1 -> 2 threads: %.2fx (target >= 1.8)\n", oracle1 / oracle2);
}
