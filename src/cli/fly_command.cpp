// vt fly TEXTURE: a camera path frame by frame with streaming (thesis chapter 4's setup): each
// frame is drawn from the current cache state, its needbuffer analysed and prioritised, and a
// budget of pages streamed for the next frame. Writes per-frame statistics (frames.csv,
// summary.json) that are the same bytes for any thread count, the run time separately
// (timing.json), and optionally every n-th frame as an image.

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/image_file.h"
#include "eval/image_metrics.h"
#include "gl/gl_frame_renderer.h"
#include "gl/headless_context.h"
#include "reference/frame_images.h"
#include "reference/renderer.h"
#include "runtime/needbuffer_scale.h"
#include "runtime/virtual_texture_runtime.h"
#include "scene/box_room.h"
#include "scene/camera_motion.h"
#include "scene/camera_path.h"
#include "scene/obj_mesh.h"
#include "shader/needbuffer.h"

namespace vt {

void addFlyCommand(CLI::App& app) {
  struct Options {
    std::string texture, path, mesh, size = "320x200", heuristic = "pixelsum", ancestors = "none";
    std::string output = "fly", backend = "oracle", lookAhead = "none", hotSpot = "shifted";
    std::string streaming = "budget", needScale = "1", profile = "auto", readback = "sync";
    double linkLatency = 0.0, linkMegabytes = 0.0;
    uint32_t budget = 10, latency = 0, lockedLevels = 0, initialLevels = 3, frames = 16;
    float noiseThreshold = -1.0f;
    bool noiseSkipping = false, preloadVisible = false, quality = false;
    unsigned threads = 0;
    int imagesEvery = 0;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "fly", "Render a camera path with streaming and write per-frame statistics");
  command->add_option("TEXTURE", o->texture, "Virtual-texture file (.vt)")->required();
  command->add_option("--path", o->path,
                      "Camera path (.json); default: a turn around the box room");
  command->add_option("--mesh", o->mesh,
                      "OBJ mesh with virtual texture coordinates (default: the box room)");
  command->add_option("--size", o->size, "WIDTHxHEIGHT")
      ->check(sizeValidator())
      ->capture_default_str();
  command->add_option("--budget", o->budget, "Pages streamed per frame (thesis 4.1.1)")
      ->capture_default_str();
  command->add_option("--latency", o->latency, "Frames between a request and its page's arrival")
      ->capture_default_str();
  command
      ->add_option("--need-scale", o->needScale,
                   "Needbuffer at 1/N of the resolution per axis, jittered per frame: 1, 2, 4, 8")
      ->check(CLI::IsMember({"1", "2", "4", "8"}))
      ->capture_default_str();
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
      ->add_option("--heuristic", o->heuristic,
                   "Factors joined by '*': random, pixelsum, distance, weightedpixel, "
                   "hotspot, noisevalue, mipgap")
      ->capture_default_str();
  command->add_option("--ancestors", o->ancestors, "Ancestor streaming: none, intern, extern")
      ->check(CLI::IsMember({"none", "intern", "extern"}))
      ->capture_default_str();
  command->add_flag("--noise-skipping", o->noiseSkipping, "NoiseValueSkipping (with extern)");
  command->add_option("--lookahead", o->lookAhead, "LookAhead camera (4.2.4): none, plain, stopfix")
      ->check(CLI::IsMember({"none", "plain", "stopfix"}))
      ->capture_default_str();
  command->add_option("--hotspot", o->hotSpot, "HotSpot centre (4.2.3.1): fixed, shifted, sliding")
      ->check(CLI::IsMember({"fixed", "shifted", "sliding"}))
      ->capture_default_str();
  command->add_option("--noise-threshold", o->noiseThreshold,
                      "NoiseValueSkipping threshold (default: the mean NoiseValue)");
  command
      ->add_option("--locked-levels", o->lockedLevels,
                   "Levels 0..K-1 never leave the cache (4.3.1)")
      ->capture_default_str();
  command
      ->add_option("--initial-levels", o->initialLevels,
                   "Levels 0..K-1 loaded before the first frame (4.2.1)")
      ->capture_default_str();
  command->add_flag("--preload-visible", o->preloadVisible,
                    "Also load the pages the first frame needs before it (4.2.1)");
  command->add_option("--cache-frames", o->frames, "The cache holds N x N frames")
      ->capture_default_str();
  command
      ->add_option("--readback", o->readback,
                   "sync, or async: the analysis sees the previous frame's needbuffer (GL: "
                   "pixel-buffer objects and a fence)")
      ->check(CLI::IsMember({"sync", "async"}))
      ->capture_default_str();
  command
      ->add_option("--profile", o->profile,
                   "Precision profile of the oracle: auto (exact; with gl, GL_RENDERER's), exact, "
                   "llvmpipe, nvidia")
      ->check(CLI::IsMember({"auto", "exact", "llvmpipe", "nvidia"}))
      ->capture_default_str();
  command->add_option("--backend", o->backend, "oracle or gl")
      ->check(CLI::IsMember({"oracle", "gl"}))
      ->capture_default_str();
  command->add_option("--threads", o->threads, "Worker threads of the oracle (0: every core)");
  command->add_flag("--quality", o->quality,
                    "Per frame RMSE, SSIM (8 x 8) and WSSIM against the frame with every page "
                    "resident (the oracle's reference image); the flight's run time excludes it");
  command->add_option("--images-every", o->imagesEvery,
                      "Write every n-th frame as an image (0: none)");
  command->add_option("-o,--output", o->output, "Output folder")->capture_default_str();
  command->callback([o] {
    validateHeuristic(o->heuristic);
    reference::RenderSettings settings;
    settings.viewport = parseSize(o->size);
    settings.threads = o->threads;
    const VirtualTextureReader reader(o->texture);
    settings.need8 = reader.description().finestLevel() <= 12;  // the narrowest encoding that fits
    const CameraPath path = o->path.empty() ? boxRoomPath() : CameraPath::load(o->path);
    const Mesh mesh = o->mesh.empty() ? boxRoom() : loadObjMesh(o->mesh);

    RuntimeOptions options;
    options.framesX = options.framesY = std::max(1u, o->frames);
    options.lockedLevels = o->lockedLevels;
    options.priority.heuristic = o->heuristic;
    options.priority.ancestors = parseAncestorStrategy(o->ancestors);
    options.priority.noiseValueSkipping = o->noiseSkipping;
    double meanNoise = 0.0;
    for (const float n : reader.noiseValues()) meanNoise += n;
    meanNoise /= static_cast<double>(std::max<size_t>(1, reader.noiseValues().size()));
    options.priority.noiseThreshold =
        o->noiseThreshold >= 0.0f ? o->noiseThreshold : static_cast<float>(meanNoise);
    VirtualTextureRuntime runtime(reader, options);
    // The initial cache state (thesis 4.2.1): levels 0..K-1 and, with --preload-visible, every
    // page the first frame needs, found by drawing it with every page resident.
    std::vector<uint64_t> initial;
    const uint32_t initialLevels = std::min(o->initialLevels, reader.description().levelCount);
    for (uint64_t p = 0; initialLevels > 0 && p < pageCount(initialLevels - 1); ++p)
      initial.push_back(p);
    // Every page resident: for the pages visible from the start and for the reference images.
    std::unique_ptr<reference::ResidentTexture> everything;
    if (o->preloadVisible || o->quality)
      everything = std::make_unique<reference::ResidentTexture>(reader);
    if (o->preloadVisible) {
      const reference::Frame first = reference::renderFrame(
          toClipSpace(mesh, path.at(0), settings.viewport), *everything, settings);
      const std::vector<uint64_t> visible = neededPages(first.need, settings.need8).pages;
      initial.insert(initial.end(), visible.begin(), visible.end());
    }
    runtime.preload(initial);
    // Deterministic budget mode for evaluations, or a thread over a link in real time.
    std::unique_ptr<BudgetStreamer> budget;
    std::unique_ptr<ThreadedStreamer> thread;
    if (o->streaming == "budget")
      budget = std::make_unique<BudgetStreamer>(reader, o->budget, o->latency);
    else
      thread = std::make_unique<ThreadedStreamer>(
          reader, LinkModel{o->linkLatency, o->linkMegabytes * 1e6});
    const LookAhead lookAhead = parseLookAhead(o->lookAhead);
    const HotSpotMode hotSpotMode = parseHotSpotMode(o->hotSpot);

    std::unique_ptr<HeadlessContext> context;
    if (o->backend == "gl") context = std::make_unique<HeadlessContext>();
    if (o->profile != "auto")
      settings.profile = reference::parsePrecisionProfile(o->profile);
    else if (context)
      settings.profile = reference::profileForRenderer(context->renderer());
    // One program and one set of textures for the whole flight (the cache keeps its layout).
    std::unique_ptr<GlFrameRenderer> gl;
    if (context) gl = std::make_unique<GlFrameRenderer>(runtime.cacheState());

    const std::filesystem::path folder = o->output;
    std::filesystem::create_directories(folder);
    std::ostringstream csv;
    csv << "frame,covered_pixels,needed_pages,hits,misses,hit_pixels,requested,streamed,evicted,"
           "resident"
        << (o->quality ? ",rmse,ssim,wssim\n" : "\n");
    // Quality against reference images: every page resident, drawn by the oracle at the screen's
    // resolution (DESIGN section 5); its time is kept apart from the flight's.
    double qualitySeconds = 0.0, rmseSum = 0.0, ssimSum = 0.0, wssimSum = 0.0, ssimMin = 1.0;
    FrameStatistics totals;
    const auto start = std::chrono::steady_clock::now();
    uint64_t streamedBefore = 0, evictedBefore = 0;
    // The needbuffer's resolution: the screen's, or 1/2^k of it, jittered from frame to frame
    // (runtime/needbuffer_scale.h).
    const int needScaleLog2 = parseNeedScale(o->needScale);
    const Viewport screen = settings.viewport;
    // With asynchronous readback the analysis sees the previous frame's needbuffer (and depth):
    // the GL path copies it through pixel-buffer objects behind a fence, the oracle keeps it.
    const bool async = o->readback == "async";
    std::vector<glm::uvec4> delayedNeed;
    std::vector<float> delayedDepth;
    // Draws a camera's view from the current cache state into `need` (and `depth` if asked), at
    // the needbuffer's resolution; the colour at the screen's when asked (with a full-resolution
    // needbuffer in the same pass). `delayed`: the main pass under asynchronous readback.
    const auto draw = [&](const Camera& camera, uint64_t frame, std::vector<uint8_t>* color,
                          std::vector<glm::uvec4>& need, std::vector<float>* depth, bool delayed) {
      const auto pass = [&](Viewport viewport, int scaleLog2, glm::vec2 jitter,
                            std::vector<uint8_t>* passColor, std::vector<glm::uvec4>* passNeed,
                            std::vector<float>* passDepth) {
        reference::RenderSettings passSettings = settings;
        passSettings.viewport = viewport;
        passSettings.needScaleLog2 = scaleLog2;
        const bool readDepth = passDepth != nullptr;
        const ClipSpaceMesh clip = toClipSpace(mesh, camera, viewport, jitter);
        if (gl) {
          gl->uploadCache();  // the management step changed it since the last draw
          if (delayed && passNeed) {
            std::optional<GlFrame> previous = gl->renderAsync(clip, passSettings, readDepth);
            if (passColor) *passColor = gl->readColor();
            *passNeed = previous ? std::move(previous->need) : std::vector<glm::uvec4>{};
            if (passDepth)
              *passDepth = previous ? std::move(previous->depth) : std::vector<float>{};
            return;
          }
          GlFrame frame = gl->render(clip, passSettings, readDepth);
          if (passColor) *passColor = std::move(frame.color);
          if (passNeed) *passNeed = std::move(frame.need);
          if (passDepth) *passDepth = std::move(frame.depth);
          return;
        }
        reference::Frame frame = reference::renderFrame(clip, runtime.cacheState(), passSettings);
        if (passColor) *passColor = std::move(frame.color);
        if (delayed && passNeed) {
          std::swap(frame.need, delayedNeed);
          if (readDepth) std::swap(frame.depth, delayedDepth);
        }
        if (passNeed) *passNeed = std::move(frame.need);
        if (passDepth) *passDepth = std::move(frame.depth);
      };
      if (needScaleLog2 == 0) return pass(screen, 0, glm::vec2(0.0f), color, &need, depth);
      pass(reducedViewport(screen, needScaleLog2), needScaleLog2, needJitter(frame, needScaleLog2),
           nullptr, &need, depth);
      if (color) pass(screen, 0, glm::vec2(0.0f), color, nullptr, nullptr);
    };
    const Viewport needViewport = reducedViewport(screen, needScaleLog2);
    for (int frameNumber = 0; frameNumber < path.frameCount(); ++frameNumber) {
      const Camera current = path.at(frameNumber), previous = path.at(std::max(0, frameNumber - 1)),
                   beforePrevious = path.at(std::max(0, frameNumber - 2));
      std::vector<uint8_t> color;
      std::vector<glm::uvec4> need, lookAheadNeed;
      std::vector<float> depth;
      const bool writeImage = o->imagesEvery > 0 && frameNumber % o->imagesEvery == 0;
      const auto frameIndex = static_cast<uint64_t>(frameNumber);
      draw(current, frameIndex, (writeImage || o->quality) ? &color : nullptr, need,
           runtime.needsDepth() ? &depth : nullptr, async);
      VirtualTextureRuntime::Prediction prediction;
      prediction.hotSpot = vt::hotSpot(previous, current, needViewport, hotSpotMode);
      if (lookAhead != LookAhead::kNone) {
        draw(lookAheadCamera(beforePrevious, previous, current, lookAhead), frameIndex, nullptr,
             lookAheadNeed, nullptr, false);
        prediction.lookAheadNeed = lookAheadNeed;
      }
      FrameStatistics statistics;
      statistics.streamed = streamedBefore;
      statistics.evicted = evictedBefore;
      // The first frame under asynchronous readback has no needbuffer yet: nothing to ask for.
      const std::vector<StreamRequest> requests =
          need.empty() ? std::vector<StreamRequest>{}
                       : runtime.analyze(need, depth, needViewport.width, needViewport.height,
                                         settings.need8, frameIndex, statistics, prediction);
      csv << frameNumber << ',' << statistics.coveredPixels << ',' << statistics.neededPages << ','
          << statistics.hits << ',' << statistics.misses << ',' << statistics.hitPixels << ','
          << statistics.requested << ',' << statistics.streamed << ',' << statistics.evicted << ','
          << statistics.resident;
      if (o->quality) {
        const auto qualityStart = std::chrono::steady_clock::now();
        reference::RenderSettings full = settings;
        full.viewport = screen;
        const reference::Frame expected =
            reference::renderFrame(toClipSpace(mesh, current, screen), *everything, full);
        const ImageView got{screen.width, screen.height, color},
            want{screen.width, screen.height, expected.color};
        const double frameRmse = rmse(got, want), frameSsim = ssim(got, want),
                     frameWssim = wssim(got, want);
        csv << ',' << frameRmse << ',' << frameSsim << ',' << frameWssim;
        rmseSum += frameRmse, ssimSum += frameSsim, wssimSum += frameWssim;
        ssimMin = std::min(ssimMin, frameSsim);
        qualitySeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - qualityStart).count();
      }
      csv << '\n';
      totals.hits += statistics.hits;
      totals.misses += statistics.misses;
      totals.streamed += statistics.streamed;
      totals.evicted += statistics.evicted;
      if (writeImage) {
        reference::Frame image;
        image.viewport = settings.viewport;
        image.color = color;
        const std::vector<uint8_t> rows = reference::colorImage(image);
        char name[32];
        std::snprintf(name, sizeof name, "frame%04d.png", frameNumber);
        writeImage8(folder / name, static_cast<uint32_t>(settings.viewport.width),
                    static_cast<uint32_t>(settings.viewport.height), 4,
                    std::as_bytes(std::span(rows)));
      }
      // Streaming for the next frame, applied by the management step.
      std::vector<StreamedPage> arrived;
      if (budget) {
        arrived = budget->frame(requests);
      } else {
        thread->request(requests);
        arrived = thread->takeStreamed();
      }
      const auto [applied, evicted] = runtime.apply(std::move(arrived));
      streamedBefore = applied;
      evictedBefore = evicted;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
        qualitySeconds;
    std::ofstream(folder / "frames.csv") << csv.str();
    nlohmann::json summary = {{"texture", o->texture},
                              {"frames", path.frameCount()},
                              {"heuristic", o->heuristic},
                              {"ancestors", o->ancestors},
                              {"noise_skipping", o->noiseSkipping},
                              {"streaming", o->streaming},
                              {"need_scale", std::stoi(o->needScale)},
                              {"readback", o->readback},
                              {"budget", o->budget},
                              {"latency", o->latency},
                              {"link_latency_seconds", o->linkLatency},
                              {"link_megabytes_per_second", o->linkMegabytes},
                              {"cache_frames", o->frames},
                              {"locked_levels", o->lockedLevels},
                              {"initial_levels", o->initialLevels},
                              {"preload_visible", o->preloadVisible},
                              {"hits", totals.hits},
                              {"misses", totals.misses},
                              {"streamed", totals.streamed},
                              {"evicted", totals.evicted},
                              {"backend", o->backend},
                              {"profile", reference::toString(settings.profile)}};
    if (o->quality) {
      const double frames = path.frameCount();
      summary["mean_rmse"] = rmseSum / frames;
      summary["mean_ssim"] = ssimSum / frames;
      summary["min_ssim"] = ssimMin;
      summary["mean_wssim"] = wssimSum / frames;
    }
    std::ofstream(folder / "summary.json") << summary.dump(2) << '\n';
    std::ofstream(folder / "timing.json") << nlohmann::json{{"seconds", seconds},
                                                            {"frames", path.frameCount()},
                                                            {"quality_seconds", qualitySeconds}}
                                                 .dump(2)
                                          << '\n';
    std::cout << "flew " << path.frameCount() << " frames in " << seconds << " s (" << o->backend
              << "): " << totals.hits << " needed-page hits, " << totals.misses << " misses, "
              << totals.streamed << " pages streamed, " << totals.evicted << " evicted; wrote "
              << (folder / "frames.csv").string() << "\n";
    if (o->quality)
      std::cout << "quality against every page resident: mean SSIM " << ssimSum / path.frameCount()
                << ", min SSIM " << ssimMin << ", mean WSSIM " << wssimSum / path.frameCount()
                << ", mean RMSE " << rmseSum / path.frameCount() << " (8-bit units), for "
                << seconds << " s of flight\n";
  });
}

}  // namespace vt
