#include "workflows/fly_to_folder.h"

#include <memory>
#include <optional>

#include "common/posix_file.h"
#include "eval/flight_records.h"
#include "render/arithmetic_points.h"
#include "shader/needbuffer.h"
#include "verify/flight_capture.h"
#include "workflows/auto_model.h"

namespace vt {

FlightResult flyToFolder(const VirtualTextureReader& reader, const FlyRequest& request,
                         std::ostream& out, std::ostream& err) {
  const CameraPath& path = request.path;
  FlightOptions options;
  options.settings.viewport = request.screen;
  options.settings.threads = request.threads;
  // The narrowest needbuffer encoding that fits.
  options.settings.need8 = need8Encodes(reader.description().finestLevel());
  options.threadedStreaming = request.threadedStreaming;
  options.link = LinkModel{request.linkLatencySeconds, request.linkMegabytesPerSecond * 1e6};
  options.backend = request.backend;
  const BackendContext context(request.backend);
  // auto: the model the implementation's fingerprint confirms (workflows/auto_model.h); the
  // oracle, which has none, flies in exact arithmetic.
  std::string note;
  options.settings.arithmetic = request.profile != "auto"
                                    ? arithmeticPoint(request.profile)
                                    : autoModel(context, &note).value_or(exactModel()).arithmetic;
  if (!note.empty()) err << "vt fly: " << note << "\n";
  // Reference images: every page resident, drawn by the oracle at the screen's resolution
  // (docs/design.md section 5).
  std::unique_ptr<const ResidentRenderer> everything;
  if (request.quality) {
    everything = makeResidentRenderer(reader);
    options.reference = [&](int frame) {
      return referenceImage(*everything, request.mesh, path.at(frame), options.settings);
    };
  }
  // Frame 0 is always captured, so its manifest marks a previous capture folder.
  TemporaryFolder staging(request.output, "summary.json");
  const std::filesystem::path folder = staging.path();
  std::optional<TemporaryFolder> captureStaging;
  if (!request.capture.empty()) captureStaging.emplace(request.capture, "frame0000.json");
  if (request.imagesEvery > 0) {
    options.wantsColor = [&](int frame) { return frame % request.imagesEvery == 0; };
    options.observe = [&](const FlightFrameView& view) {
      if (view.frame % request.imagesEvery != 0) return;
      writeColorImage(folder / frameImageName(view.frame), options.settings.viewport, view.color);
    };
  }
  if (captureStaging) {
    const std::string renderer = context.captureName(options.settings);
    // The named point this GL implementation reproduces, recorded for `--model auto`.
    const std::string fingerprint = fingerprintedPoint(context);
    options.wantsCapture = [&](int frame) { return frame % request.captureEvery == 0; };
    options.capture = [&, renderer, fingerprint](const FlightCaptureView& view) {
      writeFlightCapture(captureStaging->path(), view, reader, options.settings, renderer,
                         fingerprint);
    };
  }

  const FlightResult result = fly(reader, request.mesh, path, request.configuration, options);
  writeFlightRecords(folder, result, request.quality);
  writeFlightSummary(folder, request.configuration,
                     {.texture = request.texture.string(),
                      .frames = path.frameCount(),
                      .streaming = request.threadedStreaming ? "thread" : "budget",
                      .backend = toString(request.backend),
                      .linkLatencySeconds = request.linkLatencySeconds,
                      .linkMegabytesPerSecond = request.linkMegabytesPerSecond,
                      .arithmetic = options.settings.arithmetic},
                     result);
  if (captureStaging) captureStaging->commit();
  staging.commit();
  const FrameStatistics& totals = result.totals;
  out << "flew " << path.frameCount() << " frames in " << result.seconds << " s ("
      << toString(request.backend) << "): " << totals.hits << " needed-page hits, " << totals.misses
      << " misses, " << totals.streamed << " pages streamed, " << totals.evicted
      << " evicted; wrote " << (request.output / "frames.csv").string() << "\n";
  if (request.quality) {
    const nlohmann::json q = flightTotals(result);
    out << "quality against every page resident: mean SSIM " << q["mean_ssim"].get<double>()
        << ", min SSIM " << q["min_ssim"].get<double>() << ", mean WSSIM "
        << q["mean_wssim"].get<double>() << ", mean RMSE " << q["mean_rmse"].get<double>()
        << " (8-bit units), for " << result.seconds << " s of flight\n";
  }
  return result;
}

}  // namespace vt
