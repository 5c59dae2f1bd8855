#include "capture/streamed_flight.h"

#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "capture/capture_writer.h"
#include "common/error.h"
#include "common/posix_file.h"
#include "format/page_address.h"
#include "gl/gl_frame_renderer.h"
#include "render/check_modes.h"
#include "runtime/heuristic.h"
#include "runtime/page_streamer.h"
#include "runtime/virtual_texture_runtime.h"
#include "scene/clip_space_mesh.h"
#include "shader/needbuffer.h"

namespace vt::capture {
namespace {

// The largest cache texture side any GL 4.5 implementation must support is 16384 texels; the
// cache is refused above it rather than left to a driver's error.
constexpr uint64_t kMaxCacheSide = 16384;

RuntimeOptions runtimeOptions(const VirtualTextureReader& reader,
                              const StreamedFlightOptions& options) {
  const TextureDescription& d = reader.description();
  const uint64_t side = uint64_t{options.cacheFrames} * (d.pageSize + 2 * d.border);
  if (options.cacheFrames < 2 || side > kMaxCacheSide)
    throw InputError(reader.path(), "a cache of " + std::to_string(options.cacheFrames) +
                                        " frames a side is " + std::to_string(side) +
                                        " texels wide; it must hold 2 frames and at most " +
                                        std::to_string(kMaxCacheSide) + " texels");
  RuntimeOptions runtime;
  runtime.framesX = runtime.framesY = options.cacheFrames;
  try {
    runtime.priority.heuristic = Heuristic::parse(options.heuristic);
  } catch (const std::invalid_argument& e) {
    throw InputError(reader.path(), e.what());
  }
  return runtime;
}

// The crosscheck's mode the flight draws in (render/check_modes.h).
CheckMode flightMode(const VirtualTextureReader& reader, const StreamedFlightOptions& options) {
  const std::vector<CheckMode> modes = checkModes(reader.description().finestLevel());
  if (options.linear && modes.size() < 2)
    throw InputError(reader.path(),
                     "its levels do not fit the 8-bit needbuffer that GL_LINEAR "
                     "captures use");
  return modes[options.linear ? 1 : 0];
}

}  // namespace

StreamedFlight flyAndCapture(const VirtualTextureReader& reader, const Mesh& mesh,
                             const CameraPath& path, const StreamedFlightOptions& options,
                             const std::string& renderer, const std::filesystem::path& folder) {
  const CheckMode mode = flightMode(reader, options);
  RenderSettings settings;
  settings.viewport = options.viewport;
  applyMode(settings, mode);
  VirtualTextureRuntime runtime(reader, runtimeOptions(reader, options));
  std::vector<uint64_t> initial;
  const uint32_t levels = std::min(options.initialLevels, reader.description().levelCount);
  for (uint64_t p = 0; levels > 0 && p < pageCount(levels - 1); ++p) initial.push_back(p);
  runtime.preload(initial);
  GlFrameRenderer gl(runtime.cacheState());
  BudgetStreamer streamer(reader, options.budget);
  const std::string textureFile = options.textureName.empty()
                                      ? std::filesystem::absolute(reader.path()).string()
                                      : options.textureName;
  StreamedFlight flight;
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  for (int f = 0; f < path.frameCount(); ++f) {
    const ClipSpaceMesh view = toClipSpace(mesh, path.at(f), settings.viewport);
    if (f % options.every == 0) {
      const Frame drawn = gl.render(view, settings);
      char name[32];
      std::snprintf(name, sizeof name, "frame%04d.json", f);
      writeCapturedFrame(folder / name,
                         {renderer, textureFile, reader.identity(), &view, &runtime.cacheState(),
                          settings.need8, settings.trilinear, settings.exactFilter, &drawn,
                          nlohmann::json{{"frame", f}, {"flight", "streamed"}}});
      ++flight.captures;
    }
    const bool depth = runtime.needsDepth();
    const Frame drawn = options.asyncReadback ? gl.renderDelayed(view, settings, depth)
                                              : gl.render(view, settings, depth);
    FrameStatistics statistics;
    // Under asynchronous readback the first frame has no needbuffer yet: nothing to ask for.
    const std::vector<StreamRequest> requests =
        drawn.need.empty() ? std::vector<StreamRequest>{}
                           : runtime.analyze(drawn.need, drawn.depth, settings.viewport.width,
                                             settings.viewport.height, settings.need8,
                                             static_cast<uint64_t>(f), statistics);
    const auto [applied, evicted] = runtime.apply(streamer.frame(requests));
    if (applied > 0) gl.cacheChanged();
    flight.streamed += applied;
    flight.evicted += evicted;
    flight.misses += statistics.misses;
    frames.push_back(
        {{"frame", f}, {"misses", statistics.misses}, {"streamed", applied}, {"evicted", evicted}});
    ++flight.frames;
  }
  const nlohmann::ordered_json record = {{"renderer", renderer},
                                         {"heuristic", options.heuristic},
                                         {"budget", options.budget},
                                         {"cache_frames", options.cacheFrames},
                                         {"initial_levels", options.initialLevels},
                                         {"every", options.every},
                                         {"async_readback", options.asyncReadback},
                                         {"mode", mode.name},
                                         {"totals",
                                          {{"frames", flight.frames},
                                           {"captures", flight.captures},
                                           {"streamed", flight.streamed},
                                           {"evicted", flight.evicted},
                                           {"misses", flight.misses}}},
                                         {"frames", frames}};
  writeFileAtomically(folder / "flight.summary", record.dump(1) + "\n");
  return flight;
}

}  // namespace vt::capture
