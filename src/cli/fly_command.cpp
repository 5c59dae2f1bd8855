// vt fly TEXTURE: a camera path frame by frame with streaming (thesis chapter 4's setup): each
// frame is drawn from the current cache state, its needbuffer analysed and prioritised, and a
// budget of pages streamed for the next frame. Writes per-frame statistics (frames.csv,
// summary.json) that are the same bytes for any thread count, the run time separately
// (timing.json), and optionally every n-th frame as an image.

#include <algorithm>
#include <iostream>
#include <memory>

#include "backends/backend.h"
#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/output_path.h"
#include "common/resource_limits.h"
#include "render/arithmetic_points.h"
#include "workflows/fly_to_folder.h"

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
    const VirtualTextureReader reader(o->scene.texture);
    FlyRequest request{.texture = o->scene.texture,
                       .mesh = o->scene.loadMesh(),
                       .path = o->scene.cameraPath(),
                       .configuration = configurationOptions->configuration(),
                       .screen = parseSize(o->scene.size),
                       .threads = o->threads,
                       .backend = parseBackend(o->backend),
                       .profile = o->profile,
                       .threadedStreaming = o->streaming == "thread",
                       .linkLatencySeconds = o->linkLatency,
                       .linkMegabytesPerSecond = o->linkMegabytes,
                       .quality = o->quality,
                       .imagesEvery = o->imagesEvery,
                       .output = o->output,
                       .capture = o->capture,
                       .captureEvery = o->captureEvery};
    requirePathPixelsFit(o->scene.path.empty() ? "the box room's path" : o->scene.path,
                         static_cast<uint64_t>(request.path.frameCount()),
                         static_cast<uint64_t>(request.screen.width),
                         static_cast<uint64_t>(request.screen.height), o->quality ? 2 : 1);
    flyToFolder(reader, request, std::cout, std::cerr);
  });
}

}  // namespace vt
