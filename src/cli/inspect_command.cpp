// vt inspect TEXTURE: a frame-by-frame debugging page of one flight (eval/inspect_page.h), for
// finding out why a configuration streamed what it streamed. Per frame: the rendered image, the
// reference (every needed page resident), their difference, the needbuffer by level, the level
// each needed page resolves to, the cache atlas, the statistics, the head of the priority queue
// with each page's heuristic terms, and the pages streamed for the next frame.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/output_path.h"
#include "common/resource_limits.h"
#include "eval/flight.h"
#include "eval/inspect_images.h"
#include "eval/inspect_page.h"
#include "backends/backend.h"
#include "scene/box_room.h"
#include "scene/obj_mesh.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

constexpr int kMaxFramesInPage = 400;  // each frame embeds six images

std::string number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace

void addInspectCommand(CLI::App& app) {
  struct Options {
    FlightSceneArguments scene;
    std::string output = "inspect.html";
    int first = 0, last = -1, every = 1, queue = 24, atlasSide = 512;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "inspect", "Write a self-contained HTML page to step through a flight frame by frame");
  o->scene.addTo(command);
  auto configurationOptions = std::make_shared<ConfigurationOptions>(command);
  command->add_option("--first", o->first, "First frame shown")->capture_default_str();
  command->add_option("--last", o->last, "Last frame shown (-1: the path's last)")
      ->capture_default_str();
  command->add_option("--every", o->every, "Show every n-th frame")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_option("--queue", o->queue, "Entries of the priority queue shown per frame")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  command->add_option("--atlas-side", o->atlasSide, "Largest side of the cache atlas image")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  command->add_option("-o,--output", o->output, "HTML file")->capture_default_str();
  command->callback([o, configurationOptions] {
    std::vector<std::filesystem::path> inputs = o->scene.inputs();
    inputs.push_back(configurationOptions->file());
    requireOutputFile(o->output, inputs);
    const VirtualTextureReader reader(o->scene.texture);
    const CameraPath path = o->scene.cameraPath();
    const Mesh mesh = o->scene.loadMesh();
    const FlightConfiguration configuration = configurationOptions->configuration();
    const int last = o->last < 0 ? path.frameCount() - 1 : o->last;
    if (o->first < 0 || o->first > last || last >= path.frameCount())
      throw std::invalid_argument("frames " + std::to_string(o->first) + " to " +
                                  std::to_string(last) + " do not lie in the path's 0 to " +
                                  std::to_string(path.frameCount() - 1));
    const int shown = (last - o->first) / o->every + 1;
    if (shown > kMaxFramesInPage)
      throw std::invalid_argument(
          std::to_string(shown) + " frames asked for, a page holds at most " +
          std::to_string(kMaxFramesInPage) + ": narrow --first/--last or raise --every");
    const auto wanted = [&](int frame) {
      return frame >= o->first && frame <= last && (frame - o->first) % o->every == 0;
    };

    FlightOptions options;
    options.settings.viewport = parseSize(o->scene.size);
    // Every frame is flown; the frames shown are drawn again as reference images.
    requirePathPixelsFit(o->scene.path.empty() ? "the box room's path" : o->scene.path,
                         static_cast<uint64_t>(path.frameCount() + shown),
                         static_cast<uint64_t>(options.settings.viewport.width),
                         static_cast<uint64_t>(options.settings.viewport.height), 1);
    options.settings.need8 = need8Encodes(reader.description().finestLevel());
    options.keepAnalysis = true;
    const std::unique_ptr<const ResidentRenderer> everything = makeResidentRenderer(reader);
    // Reference images for the frames shown only.
    options.reference = [&](int frame) {
      return wanted(frame) ? referenceImage(*everything, mesh, path.at(frame), options.settings)
                           : std::vector<uint8_t>{};
    };
    const Viewport screen = options.settings.viewport;
    InspectRun run;
    run.title = "vt inspect: " + configuration.label();
    run.settings = {{"texture", o->scene.texture},
                    {"scene", o->scene.sceneName()},
                    {"path", o->scene.path.empty() ? "box room turn" : o->scene.path},
                    {"screen", o->scene.size},
                    {"configuration", configuration.toJson().dump()}};
    options.observe = [&](const FlightFrameView& view) {
      if (!wanted(view.frame)) return;
      InspectFrame frame;
      frame.frame = view.frame;
      const FrameStatistics& s = view.result.statistics;
      frame.statistics = {{"covered pixels", std::to_string(s.coveredPixels)},
                          {"needed pages", std::to_string(s.neededPages)},
                          {"hits", std::to_string(s.hits)},
                          {"misses", std::to_string(s.misses)},
                          {"requested", std::to_string(s.requested)},
                          {"streamed before this frame", std::to_string(s.streamed)},
                          {"evicted", std::to_string(s.evicted)},
                          {"resident", std::to_string(s.resident)}};
      if (view.result.quality) {
        frame.statistics.push_back({"RMSE", number(view.result.quality->rmse)});
        frame.statistics.push_back({"SSIM", number(view.result.quality->ssim)});
        frame.statistics.push_back({"WSSIM", number(view.result.quality->wssim)});
      }
      const CacheState& cache = view.runtime.cacheState();
      frame.images.push_back(rgbaImage("rendered", screen, view.color));
      frame.images.push_back(rgbaImage("reference", screen, view.reference));
      frame.images.push_back(differenceImage(screen, view.color, view.reference));
      frame.images.push_back(needbufferImage(view.needViewport, view.need, options.settings.need8));
      frame.images.push_back(
          residentLevelImage(view.needViewport, view.need, options.settings.need8, cache));
      frame.images.push_back(cacheAtlasImage(cache, o->atlasSide));
      std::set<uint64_t> streamed(view.streamed.begin(), view.streamed.end());
      for (size_t r = 0; r < view.requests.size() && r < static_cast<size_t>(o->queue); ++r) {
        const StreamRequest& request = view.requests[r];
        const PageId page = fromAbsoluteIndex(request.page);
        InspectRequest entry{request.page,
                             page.level,
                             page.x,
                             page.y,
                             request.priority,
                             {},
                             streamed.count(request.page) > 0};
        for (const auto& [name, value] : view.runtime.priorityTerms(request.page))
          entry.terms.push_back({name, value});
        if (entry.terms.empty())
          entry.terms.push_back({"ancestor: sum of children", request.priority});
        frame.queue.push_back(entry);
      }
      frame.streamed.assign(view.streamed.begin(), view.streamed.end());
      run.frames.push_back(std::move(frame));
    };
    const FlightResult result = fly(reader, mesh, path, configuration, options);
    writeInspectPage(o->output, run);
    std::cout << "wrote " << run.frames.size() << " frames of a " << path.frameCount()
              << "-frame flight (" << result.totals.streamed << " pages streamed) to " << o->output
              << "\n";
  });
}

}  // namespace vt
