#include "workflows/inspect_to_page.h"

#include <functional>
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

// What one flight showed on a frame the page holds.
struct Observed {
  int frame = 0;
  std::vector<std::pair<std::string, std::string>> statistics;
  std::vector<uint8_t> color, reference;
  InspectImage need, resident, atlas;
  InspectQueue queue;
};

std::vector<std::pair<std::string, std::string>> statisticsOf(const FlightFrame& result) {
  const FrameStatistics& s = result.statistics;
  std::vector<std::pair<std::string, std::string>> statistics = {
      {"covered pixels", std::to_string(s.coveredPixels)},
      {"needed pages", std::to_string(s.neededPages)},
      {"hits", std::to_string(s.hits)},
      {"misses", std::to_string(s.misses)},
      {"requested", std::to_string(s.requested)},
      {"streamed before this frame", std::to_string(s.streamed)},
      {"evicted", std::to_string(s.evicted)},
      {"resident", std::to_string(s.resident)}};
  if (result.quality) {
    statistics.push_back({"RMSE", number(result.quality->rmse)});
    statistics.push_back({"SSIM", number(result.quality->ssim)});
    statistics.push_back({"WSSIM", number(result.quality->wssim)});
  }
  return statistics;
}

// The head of a frame's priority queue, each request with its heuristic's terms.
InspectQueue queueOf(const FlightFrameView& view, int length, const std::string& label) {
  InspectQueue queue{label, {}, {view.streamed.begin(), view.streamed.end()}};
  const std::set<uint64_t> streamed(view.streamed.begin(), view.streamed.end());
  for (size_t r = 0; r < view.requests.size() && r < static_cast<size_t>(length); ++r) {
    const StreamRequest& request = view.requests[r];
    const PageId page = fromAbsoluteIndex(request.page);
    InspectRequest entry{request.page,     page.level, page.x, page.y, request.priority, {},
                         streamed.count(request.page) > 0};
    for (const auto& [name, value] : view.runtime.priorityTerms(request.page))
      entry.terms.push_back({name, value});
    if (entry.terms.empty()) entry.terms.push_back({"ancestor or pick", request.priority});
    queue.queue.push_back(entry);
  }
  return queue;
}

// Flies `configuration` over the whole path and keeps what the frames `wanted` showed.
std::vector<Observed> flyObserved(const VirtualTextureReader& reader, const Inspection& request,
                                  const FlightConfiguration& configuration,
                                  const std::string& label, const std::function<bool(int)>& wanted,
                                  uint64_t& streamedPages) {
  FlightOptions options;
  options.settings.viewport = request.screen;
  options.settings.need8 = need8Encodes(reader.description().finestLevel());
  options.keepAnalysis = true;
  const std::unique_ptr<const ResidentRenderer> everything = makeResidentRenderer(reader);
  // Reference images for the frames shown only.
  options.reference = [&](int frame) {
    return wanted(frame)
               ? referenceImage(*everything, request.mesh, request.path.at(frame), options.settings)
               : std::vector<uint8_t>{};
  };
  std::vector<Observed> observed;
  options.observe = [&](const FlightFrameView& view) {
    if (!wanted(view.frame)) return;
    const CacheState& cache = view.runtime.cacheState();
    const bool need8 = options.settings.need8;
    observed.push_back({view.frame,
                        statisticsOf(view.result),
                        {view.color.begin(), view.color.end()},
                        {view.reference.begin(), view.reference.end()},
                        needbufferImage(view.needViewport, view.need, need8),
                        residentLevelImage(view.needViewport, view.need, need8, cache),
                        cacheAtlasImage(cache, request.atlasSide),
                        queueOf(view, request.queue, label)});
  };
  streamedPages = fly(reader, request.mesh, request.path, configuration, options).totals.streamed;
  return observed;
}

InspectImage named(InspectImage image, const std::string& name) {
  image.name = name;
  return image;
}

// A frame of one configuration: its images, statistics and queue.
InspectFrame single(Observed& a, Viewport screen) {
  InspectFrame frame{a.frame, a.statistics, {}, {std::move(a.queue)}};
  frame.images = {rgbaImage("rendered", screen, a.color), rgbaImage("reference", screen, a.reference),
                  differenceImage(screen, a.color, a.reference), std::move(a.need),
                  std::move(a.resident), std::move(a.atlas)};
  return frame;
}

// A frame of two configurations side by side: each one's images and statistics under its label,
// where each is nearer the reference, and both queues.
InspectFrame sideBySide(Observed& a, Observed& b, Viewport screen, const std::string& labelA,
                        const std::string& labelB) {
  const auto of = [](const std::string& what, const std::string& label) {
    return what + " (" + label + ")";
  };
  InspectFrame frame{a.frame, {}, {}, {std::move(a.queue), std::move(b.queue)}};
  for (size_t k = 0; k < a.statistics.size() && k < b.statistics.size(); ++k) {
    frame.statistics.push_back({of(a.statistics[k].first, labelA), a.statistics[k].second});
    frame.statistics.push_back({of(b.statistics[k].first, labelB), b.statistics[k].second});
  }
  frame.images = {rgbaImage(of("rendered", labelA).c_str(), screen, a.color),
                  rgbaImage(of("rendered", labelB).c_str(), screen, b.color),
                  rgbaImage("reference", screen, a.reference),
                  named(differenceImage(screen, a.color, a.reference), of("difference", labelA)),
                  named(differenceImage(screen, b.color, b.reference), of("difference", labelB)),
                  comparisonImage("nearer the reference: " + labelA + " green, " + labelB +
                                      " magenta",
                                  screen, a.color, b.color, a.reference),
                  std::move(a.need),
                  named(std::move(a.resident), of("resident level", labelA)),
                  named(std::move(b.resident), of("resident level", labelB)),
                  named(std::move(a.atlas), of("cache atlas", labelA)),
                  named(std::move(b.atlas), of("cache atlas", labelB))};
  return frame;
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
  const std::function<bool(int)> wanted = [&](int frame) {
    return frame >= request.first && frame <= last && (frame - request.first) % request.every == 0;
  };
  // Every frame is flown, by each configuration; the frames shown are drawn again as references.
  const uint64_t flights = request.against ? 2 : 1;
  requirePathPixelsFit(
      request.pathFile.empty() ? std::filesystem::path("the box room's path") : request.pathFile,
      static_cast<uint64_t>(path.frameCount() + shown) * flights,
      static_cast<uint64_t>(request.screen.width), static_cast<uint64_t>(request.screen.height), 1);

  const std::string labelA = configuration.label();
  const std::string labelB = request.against ? request.against->label() : std::string();
  InspectRun run;
  run.title = "vt inspect: " + labelA + (request.against ? " against " + labelB : "");
  run.settings = {{"texture", request.texture},
                  {"scene", request.sceneName},
                  {"path", request.pathFile.empty() ? "box room turn" : request.pathFile.string()},
                  {"screen", request.screenText},
                  {"configuration", configuration.toJson().dump()}};
  uint64_t streamedA = 0, streamedB = 0;
  std::vector<Observed> a =
      flyObserved(reader, request, configuration, request.against ? labelA : "", wanted, streamedA);
  if (request.against) {
    run.settings.push_back({"against", request.against->toJson().dump()});
    std::vector<Observed> b = flyObserved(reader, request, *request.against, labelB, wanted, streamedB);
    for (size_t k = 0; k < a.size() && k < b.size(); ++k)
      run.frames.push_back(sideBySide(a[k], b[k], request.screen, labelA, labelB));
  } else {
    for (Observed& frame : a) run.frames.push_back(single(frame, request.screen));
  }
  writeInspectPage(request.output, run);
  out << "wrote " << run.frames.size() << " frames of a " << path.frameCount() << "-frame flight ("
      << streamedA << " pages streamed";
  if (request.against) out << "; " << streamedB << " by " << labelB;
  out << ") to " << request.output.string() << "\n";
}

}  // namespace vt
