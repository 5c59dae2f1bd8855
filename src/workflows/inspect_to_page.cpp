#include "workflows/inspect_to_page.h"

#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "backends/backend.h"
#include "common/resource_limits.h"
#include "eval/flight.h"
#include "eval/inspect_images.h"
#include "eval/inspect_page.h"
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

void inspectToPage(const VirtualTextureReader& reader, const Inspection& request,
                   std::ostream& out) {
  const CameraPath& path = request.path;
  const FlightConfiguration& configuration = request.configuration;
  const int last = request.last < 0 ? path.frameCount() - 1 : request.last;
  if (request.first < 0 || request.first > last || last >= path.frameCount())
    throw std::invalid_argument("frames " + std::to_string(request.first) + " to " +
                                std::to_string(last) + " do not lie in the path's 0 to " +
                                std::to_string(path.frameCount() - 1));
  const int shown = (last - request.first) / request.every + 1;
  if (shown > kMaxFramesInPage)
    throw std::invalid_argument(std::to_string(shown) + " frames asked for, a page holds at most " +
                                std::to_string(kMaxFramesInPage) +
                                ": narrow --first/--last or raise --every");
  const auto wanted = [&](int frame) {
    return frame >= request.first && frame <= last && (frame - request.first) % request.every == 0;
  };

  FlightOptions options;
  options.settings.viewport = request.screen;
  // Every frame is flown; the frames shown are drawn again as reference images.
  requirePathPixelsFit(
      request.pathFile.empty() ? std::filesystem::path("the box room's path") : request.pathFile,
      static_cast<uint64_t>(path.frameCount() + shown),
      static_cast<uint64_t>(options.settings.viewport.width),
      static_cast<uint64_t>(options.settings.viewport.height), 1);
  options.settings.need8 = need8Encodes(reader.description().finestLevel());
  options.keepAnalysis = true;
  const std::unique_ptr<const ResidentRenderer> everything = makeResidentRenderer(reader);
  // Reference images for the frames shown only.
  options.reference = [&](int frame) {
    return wanted(frame)
               ? referenceImage(*everything, request.mesh, path.at(frame), options.settings)
               : std::vector<uint8_t>{};
  };
  const Viewport screen = options.settings.viewport;
  InspectRun run;
  run.title = "vt inspect: " + configuration.label();
  run.settings = {{"texture", request.texture},
                  {"scene", request.sceneName},
                  {"path", request.pathFile.empty() ? "box room turn" : request.pathFile.string()},
                  {"screen", request.screenText},
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
    frame.images.push_back(cacheAtlasImage(cache, request.atlasSide));
    std::set<uint64_t> streamed(view.streamed.begin(), view.streamed.end());
    for (size_t r = 0; r < view.requests.size() && r < static_cast<size_t>(request.queue); ++r) {
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
  const FlightResult result = fly(reader, request.mesh, path, configuration, options);
  writeInspectPage(request.output, run);
  out << "wrote " << run.frames.size() << " frames of a " << path.frameCount() << "-frame flight ("
      << result.totals.streamed << " pages streamed) to " << request.output.string() << "\n";
}

}  // namespace vt
