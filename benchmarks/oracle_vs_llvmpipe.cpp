// Time per frame of the CPU oracle against Mesa's llvmpipe drawing the same frames with the GL
// renderer's own shader (the shared virtual-texture logic), in the same process, from the same
// cache state. Scenes: a generated terrain of 20,000 triangles with every page resident, and
// real maps given on the command line (a texture, its mesh and a camera path: tour frames spread
// over the path, from a cache of the map's coarser levels that fits one 8192^2 texture). Each at
// 1280 x 720 and 1920 x 1080; llvmpipe with LP_NUM_THREADS=2, the oracle with 2 and 1 threads
// under the pinned llvmpipe model and with 2 threads under gl45: as `vt crosscheck` judges a frame
// (result sets where llvmpipe's frame of the same view differs from the oracle's own value,
// RenderSettings::judged), and with every pixel's set (`--all-sets`). Prints one row per scene and
// size: the medians, the ratio oracle / llvmpipe (target <= 1.0), the oracle's scaling from 1 to
// 2 threads (target >= 1.8), the cost of gl45 over the pinned model (target <= 2.0), the share of
// pixels whose set was built, and the cost of every pixel's set over the pinned model.
// benchmarks/oracle_vs_llvmpipe.sh builds the maps and runs this three times.
// --pinned-only leaves gl45 out (quick runs, profiles of the pinned path). --census adds, per
// row, what gl45's sets hold: the pixels whose set is one triangle's alternative, those with
// several or with the empty one besides, and the empty pixels, each with its share of the
// triangles' alternatives (each costs a fragment's and a colour's bounds; the empty one
// nothing).
//   usage: oracle_vs_llvmpipe [--frames N] [--pinned-only] [--census] [--map NAME TEXTURE.vt
//          MESH.obj PATH.json]...

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "build/synthetic_texture.h"
#include "gl/gl_frame_renderer.h"
#include "gl/headless_context.h"
#include "reference/renderer.h"
#include "render/arithmetic_points.h"
#include "render/cache_state.h"
#include "scene/camera.h"
#include "scene/camera_path.h"
#include "scene/obj_mesh.h"

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

// One scene to time: its mesh, the cameras of its frames and the cache state both renderers draw.
struct Scene {
  std::string name;
  vt::Mesh mesh;
  std::vector<vt::Camera> cameras;
  std::unique_ptr<vt::CacheState> cache;
};

// The median over `repeats` runs of the time to draw every camera of a scene once.
template <class Draw>
double medianMilliseconds(int repeats, Draw draw) {
  std::vector<double> times;
  for (int k = 0; k < repeats; ++k) {
    const auto start = std::chrono::steady_clock::now();
    draw();
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

Scene terrainScene(const std::filesystem::path& file) {
  vt::writeSyntheticTexture(
      file, {{.pageSize = 128, .border = 4, .levelCount = 5, .channels = 4}, std::nullopt});
  const vt::VirtualTextureReader reader(file);
  std::vector<uint64_t> pages(reader.storedPageCount());
  for (uint64_t p = 0; p < pages.size(); ++p) pages[p] = p;
  Scene scene{"terrain", terrain(), {}, nullptr};
  scene.cache = std::make_unique<vt::CacheState>(vt::makeCacheState(reader, pages, 19, 19));
  vt::Camera camera;
  camera.position = {0, 18, 45};
  camera.target = {0, 0, 0};
  scene.cameras.push_back(camera);
  return scene;
}

// Four tour frames spread over the path (its first and last frame included).
Scene mapScene(const std::string& name, const std::filesystem::path& texture,
               const std::filesystem::path& mesh, const std::filesystem::path& path) {
  const vt::VirtualTextureReader reader(texture);
  Scene scene{name, vt::loadObjMesh(mesh), {}, nullptr};
  scene.cache = std::make_unique<vt::CacheState>(vt::cacheOfLevels(reader, -1, 8192));
  const vt::CameraPath cameras = vt::CameraPath::load(path);
  constexpr int kFrames = 4;
  for (int k = 0; k < kFrames; ++k)
    scene.cameras.push_back(cameras.at(k * (cameras.frameCount() - 1) / (kFrames - 1)));
  return scene;
}

int usage() {
  std::fprintf(stderr,
               "usage: oracle_vs_llvmpipe [--frames N] [--pinned-only] [--census] [--map NAME "
               "TEXTURE.vt MESH.obj PATH.json]...\n");
  return 2;
}

// Pixels and alternatives of a frame's sets by kind: one triangle's alternative alone, several
// (or a triangle's and the empty one), empty only.
struct Census {
  std::array<uint64_t, 3> pixels{}, alternatives{};  // alternatives: those with a triangle
  void add(const vt::ResultSets& sets) {
    for (size_t i = 0; i + 1 < sets.offsets.size(); ++i) {
      const uint32_t first = sets.offsets[i], last = sets.offsets[i + 1];
      uint32_t triangles = 0;
      for (uint32_t k = first; k < last; ++k) triangles += sets.alternatives[k].triangle >= 0;
      const size_t kind = triangles == 0 ? 2 : last - first == 1 ? 0 : 1;
      ++pixels[kind];
      alternatives[kind] += triangles;
    }
  }
  void print() const {
    const double p = static_cast<double>(pixels[0] + pixels[1] + pixels[2]);
    const double a = static_cast<double>(alternatives[0] + alternatives[1] + alternatives[2]);
    const char* const names[3] = {"one alternative", "several", "empty"};
    std::printf("  census:");
    for (size_t k = 0; k < 3; ++k)
      std::printf(" %s %.1f%% of pixels (%.1f%% of alternatives)%s", names[k],
                  100.0 * static_cast<double>(pixels[k]) / p,
                  100.0 * static_cast<double>(alternatives[k]) / a, k < 2 ? "," : "\n");
  }
};

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5;
  bool pinnedOnly = false, census = false;
  struct MapArguments {
    std::string name, texture, mesh, path;
  };
  std::vector<MapArguments> maps;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--pinned-only") == 0) {
      pinnedOnly = true;
    } else if (std::strcmp(argv[i], "--census") == 0) {
      census = true;
    } else if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else if (std::strcmp(argv[i], "--map") == 0 && i + 4 < argc) {
      maps.push_back({argv[i + 1], argv[i + 2], argv[i + 3], argv[i + 4]});
      i += 4;
    } else {
      return usage();
    }
  }
  ::setenv("LP_NUM_THREADS", "2", 1);
  const auto file = std::filesystem::temp_directory_path() /
                    ("vt-oracle-bench-" + std::to_string(::getpid()) + ".vt");
  std::vector<Scene> scenes;
  scenes.push_back(terrainScene(file));
  std::filesystem::remove(file);
  try {
    for (const MapArguments& map : maps)
      scenes.push_back(mapScene(map.name, map.texture, map.mesh, map.path));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oracle_vs_llvmpipe: %s\n", e.what());
    return 1;
  }

  const vt::HeadlessContext context;
  std::printf("%s (%s), LP_NUM_THREADS=2; oracle under the pinned llvmpipe model unless gl45\n",
              context.renderer().c_str(), context.version().c_str());
  std::printf("%-12s %-9s %6s %9s %10s %10s %10s %8s %8s %9s %7s %9s %8s\n", "scene", "size",
              "frames", "llvmpipe", "oracle-2t", "oracle-1t", "gl45-2t", "ratio", "scaling",
              "gl45/pin", "sets%", "all-2t", "all/pin");
  const auto pinned = std::make_shared<const vt::PrecisionModel>(vt::llvmpipeModel());
  const auto gl45 = std::make_shared<const vt::PrecisionModel>(vt::gl45Model());
  for (const Scene& scene : scenes)
    for (const vt::Viewport viewport : {vt::Viewport{1280, 720}, vt::Viewport{1920, 1080}}) {
      std::vector<vt::ClipSpaceMesh> frames;
      for (const vt::Camera& camera : scene.cameras)
        frames.push_back(vt::toClipSpace(scene.mesh, camera, viewport));
      vt::RenderSettings settings;
      settings.viewport = viewport;
      vt::applyModel(settings, *pinned);
      settings.model = pinned;

      vt::GlFrameRenderer gl(*scene.cache);
      // llvmpipe's frames, to be judged under gl45; the draws compile and warm up.
      struct Drawn {
        std::vector<uint8_t> color;
        std::vector<uint32_t> need;
      };
      std::vector<Drawn> drawn;
      for (const vt::ClipSpaceMesh& mesh : frames) {
        const vt::Frame f = gl.render(mesh, settings);
        Drawn d{f.color, {}};
        for (const glm::uvec4& v : f.need) d.need.insert(d.need.end(), {v.x, v.y, v.z, v.w});
        drawn.push_back(std::move(d));
      }
      const double llvmpipe = medianMilliseconds(repeats, [&] {
        for (const vt::ClipSpaceMesh& mesh : frames) gl.draw(mesh, settings);
      });
      // Like the GL renderer's targets, the oracle's frame is reused from frame to frame. Judging,
      // each frame's sets are built where llvmpipe's frame of the same view differs.
      vt::Frame frame;
      const auto oracle = [&](vt::RenderSettings s, bool judging = false) {
        const auto draw = [&](size_t k) {
          if (judging) s.judged = {drawn[k].color, drawn[k].need};
          vt::reference::renderFrame(frames[k], *scene.cache, s, frame);
        };
        draw(0);  // warm up
        return medianMilliseconds(repeats, [&] {
          for (size_t k = 0; k < frames.size(); ++k) draw(k);
        });
      };
      // The share of pixels whose set a judging frame builds.
      const auto builtShare = [&](vt::RenderSettings s) {
        uint64_t built = 0, pixels = 0;
        for (size_t k = 0; k < frames.size(); ++k) {
          s.judged = {drawn[k].color, drawn[k].need};
          vt::reference::renderFrame(frames[k], *scene.cache, s, frame);
          for (size_t i = 0; i + 1 < frame.sets.offsets.size(); ++i) built += frame.sets.built(i);
          pixels += frame.sets.offsets.size() - 1;
        }
        return pixels ? 100.0 * static_cast<double>(built) / static_cast<double>(pixels) : 0.0;
      };
      settings.threads = 2;
      const double oracle2 = oracle(settings);
      settings.threads = 1;
      const double oracle1 = oracle(settings);
      vt::RenderSettings bounded = settings;
      vt::applyModel(bounded, *gl45);
      bounded.model = gl45;
      bounded.threads = 2;
      const double sets2 = pinnedOnly ? std::nan("") : oracle(bounded, true);
      const double all2 = pinnedOnly ? std::nan("") : oracle(bounded);
      const double share = pinnedOnly ? std::nan("") : builtShare(bounded);

      const double count = static_cast<double>(frames.size());
      const std::string size =
          std::to_string(viewport.width) + "x" + std::to_string(viewport.height);
      std::printf(
          "%-12s %-9s %6zu %9.1f %10.1f %10.1f %10.1f %7.2fx %7.2fx %8.2fx %6.2f%% %9.1f %7.2fx\n",
          scene.name.c_str(), size.c_str(), frames.size(), llvmpipe / count, oracle2 / count,
          oracle1 / count, sets2 / count, oracle2 / llvmpipe, oracle1 / oracle2, sets2 / oracle2,
          share, all2 / count, all2 / oracle2);
      if (census && !pinnedOnly) {
        Census counts;
        for (const vt::ClipSpaceMesh& mesh : frames) {
          vt::reference::renderFrame(mesh, *scene.cache, bounded, frame);
          counts.add(frame.sets);
        }
        counts.print();
      }
      std::fflush(stdout);
    }
  std::printf(
      "times: ms per frame, median of %d; ratio = oracle-2t / llvmpipe (target <= 1.0), scaling = "
      "oracle-1t / oracle-2t (target >= 1.8), gl45/pin = gl45-2t / oracle-2t (target <= 2.0), "
      "gl45-2t judging llvmpipe's frames (sets%% of pixels get a set), all-2t every pixel's set\n",
      repeats);
}
