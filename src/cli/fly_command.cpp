// vt fly TEXTURE: a camera path frame by frame with streaming (thesis chapter 4's setup): each
// frame is drawn from the current cache state, its needbuffer analysed and prioritised, and a
// budget of pages streamed for the next frame. Writes per-frame statistics (frames.csv,
// summary.json) that are the same bytes for any thread count, the run time separately
// (timing.json), and optionally every n-th frame as an image.

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "common/resource_limits.h"
#include "eval/flight.h"
#include "eval/flight_records.h"
#include "render/arithmetic_points.h"
#include "backends/backend.h"
#include "runtime/needbuffer_scale.h"
#include "scene/box_room.h"
#include "scene/camera_path.h"
#include "scene/obj_mesh.h"
#include "shader/needbuffer.h"
#include "verify/flight_capture.h"

namespace vt {
namespace {

// One folder is the other or lies inside it (compared as absolute paths, links resolved).
bool nested(const std::filesystem::path& a, const std::filesystem::path& b) {
  const auto resolved = [](const std::filesystem::path& p) {
    // Without a trailing separator, whose empty last component would compare as a name.
    const std::filesystem::path r = std::filesystem::weakly_canonical(std::filesystem::absolute(p));
    return r.filename().empty() ? r.parent_path() : r;
  };
  const std::filesystem::path x = resolved(a), y = resolved(b);
  const auto within = [](const std::filesystem::path& inner, const std::filesystem::path& outer) {
    return std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end()).first ==
           outer.end();
  };
  return within(x, y) || within(y, x);
}

}  // namespace

void addFlyCommand(CLI::App& app) {
  struct Options {
    FlightSceneArguments scene;
    std::string output = "fly", backend = "oracle";
    std::string streaming = "budget", profile = "auto", capture;
    double linkLatency = 0.0, linkMegabytes = 0.0;
    bool quality = false;
    unsigned threads = 0;
    int imagesEvery = 0, captureEvery = 1;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "fly", "Render a camera path with streaming and write per-frame statistics");
  o->scene.addTo(command);
  auto configurationOptions = std::make_shared<ConfigurationOptions>(command);
  command
      ->add_option("--streaming", o->streaming,
                   "budget (deterministic, pages per frame) or thread (a streaming thread in real "
                   "time, over the link below)")
      ->check(CLI::IsMember({"budget", "thread"}))
      ->capture_default_str();
  command->add_option("--link-latency", o->linkLatency, "With thread: seconds each page travels")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  command
      ->add_option("--link-bandwidth", o->linkMegabytes,
                   "With thread: link bandwidth in MB/s (10^6 bytes; 0 unlimited)")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  command
      ->add_option("--profile", o->profile,
                   "Precision profile of the oracle: auto (exact; with gl, GL_RENDERER's), " +
                       joinedArithmeticPointNames())
      ->check(CLI::IsMember([] {
        std::vector<std::string> names = arithmeticPointNames();
        names.insert(names.begin(), "auto");
        return names;
      }()))
      ->capture_default_str();
  command->add_option("--backend", o->backend, "oracle or gl")
      ->check(CLI::IsMember({"oracle", "gl"}))
      ->capture_default_str();
  command->add_option("--threads", o->threads, "Worker threads of the oracle (0: every core)")
      ->check(workerCount());
  command->add_flag("--quality", o->quality,
                    "Per frame RMSE, SSIM (8 x 8) and WSSIM against the frame with every page "
                    "resident (the oracle's reference image); the flight's run time excludes it");
  command->add_option("--images-every", o->imagesEvery,
                      "Write every n-th frame as an image (0: none)");
  command->add_option("--capture", o->capture,
                      "Write frames as captures for `vt crosscheck --captures` into this folder: "
                      "each drawn again at full resolution from the frame's cache state");
  command->add_option("--capture-every", o->captureEvery, "With --capture: every n-th frame")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_option("-o,--output", o->output, "Output folder")->capture_default_str();
  command->callback([o, configurationOptions] {
    std::vector<std::filesystem::path> inputs = o->scene.inputs();
    inputs.push_back(configurationOptions->file());
    requireOutputFolder(o->output, inputs);
    if (!o->capture.empty()) {
      // Each folder takes its place whole once the flight is complete.
      if (nested(o->capture, o->output))
        throw CLI::ValidationError("--capture",
                                   "the capture folder and the output folder may not lie in "
                                   "one another");
      requireOutputFolder(o->capture, inputs);
    }
    FlightOptions options;
    options.settings.viewport = parseSize(o->scene.size);
    options.settings.threads = o->threads;
    const VirtualTextureReader reader(o->scene.texture);
    // The narrowest needbuffer encoding that fits.
    options.settings.need8 = need8Encodes(reader.description().finestLevel());
    const CameraPath path = o->scene.cameraPath();
    requirePathPixelsFit(o->scene.path.empty() ? "the box room's path" : o->scene.path,
                         static_cast<uint64_t>(path.frameCount()),
                         static_cast<uint64_t>(options.settings.viewport.width),
                         static_cast<uint64_t>(options.settings.viewport.height),
                         o->quality ? 2 : 1);
    const Mesh mesh = o->scene.loadMesh();

    const FlightConfiguration configuration = configurationOptions->configuration();
    options.threadedStreaming = o->streaming == "thread";
    options.link = LinkModel{o->linkLatency, o->linkMegabytes * 1e6};
    options.backend = parseBackend(o->backend);
    const BackendContext context(options.backend);
    // auto: the model the implementation's fingerprint confirms (BackendContext::autoModel);
    // the oracle, which has none, flies in exact arithmetic.
    std::string note;
    options.settings.arithmetic = o->profile != "auto"
                                      ? arithmeticPoint(o->profile)
                                      : context.autoModel(&note).value_or(exactModel()).arithmetic;
    if (!note.empty()) std::cerr << "vt fly: " << note << "\n";
    // Reference images: every page resident, drawn by the oracle at the screen's resolution
    // (DESIGN section 5).
    std::unique_ptr<const ResidentRenderer> everything;
    if (o->quality) {
      everything = makeResidentRenderer(reader);
      options.reference = [&](int frame) {
        return referenceImage(*everything, mesh, path.at(frame), options.settings);
      };
    }
    // The frames and records, and the captures, go into temporary folders that take the outputs'
    // places once the flight is complete: a failure, early or late, leaves the previous outputs or
    // none. Frame 0 is always captured, so its manifest marks a previous capture folder.
    TemporaryFolder staging(o->output, "summary.json");
    const std::filesystem::path folder = staging.path();
    std::optional<TemporaryFolder> captureStaging;
    if (!o->capture.empty()) captureStaging.emplace(o->capture, "frame0000.json");
    if (o->imagesEvery > 0) {
      options.wantsColor = [&](int frame) { return frame % o->imagesEvery == 0; };
      options.observe = [&](const FlightFrameView& view) {
        if (view.frame % o->imagesEvery != 0) return;
        char name[32];
        std::snprintf(name, sizeof name, "frame%04d.png", view.frame);
        writeColorImage(folder / name, options.settings.viewport, view.color);
      };
    }

    if (!o->capture.empty()) {
      const std::string renderer = context.captureName(options.settings);
      // The named point this GL implementation reproduces, recorded for `--model auto`.
      const std::string fingerprint = context.fingerprintedPoint();
      options.wantsCapture = [&](int frame) { return frame % o->captureEvery == 0; };
      options.capture = [&, renderer, fingerprint](const FlightCaptureView& view) {
        writeFlightCapture(captureStaging->path(), view, reader, options.settings, renderer,
                           fingerprint);
      };
    }

    const FlightResult result = fly(reader, mesh, path, configuration, options);
    writeFlightRecords(folder, result, o->quality);
    writeFlightSummary(folder, configuration,
                       {.texture = o->scene.texture,
                        .frames = path.frameCount(),
                        .streaming = o->streaming,
                        .backend = o->backend,
                        .linkLatencySeconds = o->linkLatency,
                        .linkMegabytesPerSecond = o->linkMegabytes,
                        .arithmetic = options.settings.arithmetic},
                       result);
    if (captureStaging) captureStaging->commit();
    staging.commit();
    const FrameStatistics& totals = result.totals;
    std::cout << "flew " << path.frameCount() << " frames in " << result.seconds << " s ("
              << o->backend << "): " << totals.hits << " needed-page hits, " << totals.misses
              << " misses, " << totals.streamed << " pages streamed, " << totals.evicted
              << " evicted; wrote " << (std::filesystem::path(o->output) / "frames.csv").string()
              << "\n";
    if (o->quality) {
      const nlohmann::json q = flightTotals(result);
      std::cout << "quality against every page resident: mean SSIM " << q["mean_ssim"].get<double>()
                << ", min SSIM " << q["min_ssim"].get<double>() << ", mean WSSIM "
                << q["mean_wssim"].get<double>() << ", mean RMSE " << q["mean_rmse"].get<double>()
                << " (8-bit units), for " << result.seconds << " s of flight\n";
    }
  });
}

}  // namespace vt
