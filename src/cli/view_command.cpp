// vt view TEXTURE: an interactive window (GLFW) that flies through a scene and streams its pages
// live with the streaming thread, the chosen heuristic and an optional slow link; a HUD shows the
// frame time, pages resident, requested and streamed, and cache occupancy. Keys: W A S D to move,
// Q E down and up, the left mouse button held to look, Shift to go fast, R to start and stop
// recording the camera path (written with --record), Escape to quit. --frames, --screenshot,
// --path and --recording let scripts and tests drive it.

#include <epoxy/gl.h>
// GLFW after epoxy, without its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/image_file.h"
#include "common/output_path.h"
#include "eval/flight_run.h"
#include "eval/frame_drawer.h"
#include "eval/frame_plan.h"
#include "gl/gl_frame_renderer.h"
#include "gl/hud_overlay.h"
#include "gl/window_context.h"
#include "render/frame_images.h"
#include "runtime/needbuffer_scale.h"
#include "runtime/page_streamer.h"
#include "runtime/virtual_texture_runtime.h"
#include "scene/box_room.h"
#include "scene/camera_motion.h"
#include "scene/camera_path.h"
#include "scene/fly_camera.h"
#include "scene/obj_mesh.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

FlyInput readInput(WindowContext& window, glm::dvec2& lastCursor) {
  FlyInput input;
  const auto axis = [&](int negative, int positive) {
    return (window.keyDown(positive) ? 1.0f : 0.0f) - (window.keyDown(negative) ? 1.0f : 0.0f);
  };
  input.move = {axis(GLFW_KEY_A, GLFW_KEY_D), axis(GLFW_KEY_Q, GLFW_KEY_E),
                axis(GLFW_KEY_S, GLFW_KEY_W)};
  const glm::dvec2 cursor = window.cursor();
  if (window.mouseButtonDown(GLFW_MOUSE_BUTTON_LEFT))
    input.look = glm::vec2(static_cast<float>(cursor.x - lastCursor.x),
                           static_cast<float>(lastCursor.y - cursor.y)) *
                 0.004f;
  lastCursor = cursor;
  return input;
}

}  // namespace

void addViewCommand(CLI::App& app) {
  struct Options {
    std::string texture, mesh, camera, path, record, screenshot, size = "1280x720";
    double linkLatency = 0.0, linkMegabytes = 0.0, speed = 3.0;
    int maxFrames = 0;
    bool recordFromStart = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "view", "Fly through a scene in a window, streaming its pages live (needs a display)");
  command->add_option("TEXTURE", o->texture, "Virtual-texture file (.vt)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--mesh", o->mesh, "OBJ mesh with virtual texture coordinates (box room)")
      ->check(CLI::ExistingFile);
  command->add_option("--camera", o->camera, "x,y,z:tx,ty,tz[:fov]: where to start")
      ->check(cameraValidator());
  command->add_option("--path", o->path, "Play this camera path instead of flying by hand")
      ->check(CLI::ExistingFile);
  command->add_option("--size", o->size, "Window WIDTHxHEIGHT")
      ->check(sizeValidator())
      ->capture_default_str();
  // The flight's configuration as vt fly takes it; the budget gives way to the streaming thread.
  auto configurationOptions = std::make_shared<ConfigurationOptions>(command);
  command->add_option("--link-latency", o->linkLatency, "Seconds each page travels")
      ->check(CLI::Range(0.0, 3600.0));
  command->add_option("--link-bandwidth", o->linkMegabytes, "MB/s of the link (0 unlimited)")
      ->check(CLI::Range(0.0, 1e9));
  command->add_option("--speed", o->speed, "World units per second (Shift: 4x)")
      ->check(CLI::Range(1e-6, 1e6))
      ->capture_default_str();
  command->add_option("--record", o->record, "Where R writes the recorded camera path (.json)");
  command->add_flag("--recording", o->recordFromStart, "Record from the first frame (R stops)");
  command->add_option("--frames", o->maxFrames, "Quit after N frames (0: when closed)")
      ->check(CLI::Range(0, 1 << 30));
  command->add_option("--screenshot", o->screenshot, "Write the last frame (with HUD) as image");
  command->callback([o, configurationOptions] {
    const std::vector<std::filesystem::path> inputs = {o->texture, o->mesh, o->path,
                                                       configurationOptions->file()};
    if (!o->record.empty()) requireOutputFile(o->record, inputs);
    if (!o->screenshot.empty()) requireOutputFile(o->screenshot, inputs);
    const VirtualTextureReader reader(o->texture);
    const Mesh mesh = o->mesh.empty() ? boxRoom() : loadObjMesh(o->mesh);
    std::unique_ptr<CameraPath> path;
    if (!o->path.empty()) path = std::make_unique<CameraPath>(CameraPath::load(o->path));
    Camera camera = path                ? path->at(0)
                    : o->camera.empty() ? boxRoomCamera()
                                        : parseCamera(o->camera);

    // The thesis's interactive setup (4.2.1): levels 0..2 first (the configuration's default), a
    // streaming thread over the link. Each frame draws what its plan says (eval/frame_plan.h), as
    // vt fly would for the same configuration.
    const FlightConfiguration configuration = configurationOptions->configuration();
    FlightOptions flight;
    flight.settings.need8 = need8Encodes(reader.description().finestLevel());
    flight.threadedStreaming = true;
    flight.link = {o->linkLatency, o->linkMegabytes * 1e6};
    const Viewport size = parseSize(o->size);
    FlightRun run(reader, configuration, flight,
                  reducedViewport(size, configuration.needScaleLog2),
                  initialPages(reader, configuration, {}, flight.settings.need8));
    WindowContext window(size.width, size.height, "vt view: " + o->texture);
    GlFrameRenderer gl(run.runtime().cacheState());
    FrameDrawer drawer(mesh, flight.settings);
    drawer.attach(gl);
    DrawnPasses drawn;
    HudOverlay hud;
    std::vector<Keyframe> recorded;
    bool recording = o->recordFromStart;
    glm::dvec2 cursor = window.cursor();
    using Clock = std::chrono::steady_clock;
    Clock::time_point last = Clock::now();
    double frameMs = 0.0;
    uint64_t streamedTotal = 0;
    Camera previous = camera, beforePrevious = camera;
    for (int frame = 0; !window.shouldClose(); ++frame) {
      const Clock::time_point now = Clock::now();
      const auto seconds = static_cast<float>(std::chrono::duration<double>(now - last).count());
      last = now;
      if (window.keyPressed(GLFW_KEY_ESCAPE)) window.close();
      if (window.keyPressed(GLFW_KEY_R)) {
        recording = !recording;
        if (!recording && !o->record.empty() && recorded.size() >= 2) {
          saveCameraPath(o->record, recorded);
          std::cout << "recorded " << recorded.size() << " keyframes to " << o->record << "\n";
        }
      }
      beforePrevious = previous;
      previous = camera;
      if (path) {
        camera = path->at(frame);
      } else {
        const float fast = window.keyDown(GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.0f;
        camera = flyCamera(camera, readInput(window, cursor), seconds,
                           static_cast<float>(o->speed) * fast);
      }
      if (recording) recorded.push_back({static_cast<int>(recorded.size()), camera, std::nullopt});

      // Draw from the cache as it is, analyse, ask the thread, apply what arrived.
      const glm::ivec2 windowSize = window.framebufferSize();
      const FramePlan plan =
          planFrame(configuration, {std::max(1, windowSize.x), std::max(1, windowSize.y)},
                    static_cast<uint64_t>(frame), beforePrevious, previous, camera);
      const auto drawStart = Clock::now();
      drawer.draw(plan, ViewColor::kShown, run.runtime().needsDepth(), drawn);
      run.frame(frame, plan.previous, plan.camera,
                DrawnFrame{.need = drawn.need,
                           .depth = drawn.depth,
                           .lookAheadNeed = drawn.lookAheadNeed,
                           .needViewport = plan.need.viewport},
                std::chrono::duration<double>(Clock::now() - drawStart).count());
      const FrameStatistics& statistics = run.frames().back().statistics;
      streamedTotal += statistics.streamed;

      gl.present(windowSize);
      char lines[4][96];
      std::snprintf(lines[0], sizeof lines[0], "FRAME %d  %.1f MS%s", frame, frameMs,
                    recording ? "  REC" : "");
      std::snprintf(lines[1], sizeof lines[1], "PAGES NEEDED %llu  MISSING %llu",
                    static_cast<unsigned long long>(statistics.neededPages),
                    static_cast<unsigned long long>(statistics.misses));
      std::snprintf(lines[2], sizeof lines[2], "REQUESTED %llu  STREAMED %llu (%llu)",
                    static_cast<unsigned long long>(statistics.requested),
                    static_cast<unsigned long long>(statistics.streamed),
                    static_cast<unsigned long long>(streamedTotal));
      const uint32_t capacity = configuration.cacheFrames * configuration.cacheFrames;
      std::snprintf(lines[3], sizeof lines[3], "RESIDENT %llu / %u  %.0f%%",
                    static_cast<unsigned long long>(statistics.resident), capacity,
                    100.0 * static_cast<double>(statistics.resident) / capacity);
      hud.draw(renderHudText({lines[0], lines[1], lines[2], lines[3]}, 2), windowSize);

      const bool lastFrame = o->maxFrames > 0 && frame + 1 >= o->maxFrames;
      if (lastFrame && !o->screenshot.empty()) {
        Frame shot;  // rows bottom to top, as GL reads them
        shot.viewport = {windowSize.x, windowSize.y};
        shot.color.resize(size_t(windowSize.x) * size_t(windowSize.y) * 4);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);  // the window's, not the renderer's target
        glReadBuffer(GL_BACK);
        glReadPixels(0, 0, windowSize.x, windowSize.y, GL_RGBA, GL_UNSIGNED_BYTE,
                     shot.color.data());
        const std::vector<uint8_t> rows = colorImage(shot);
        writeImage8(o->screenshot, static_cast<uint32_t>(windowSize.x),
                    static_cast<uint32_t>(windowSize.y), 4, std::as_bytes(std::span(rows)));
      }
      window.swapAndPoll();
      frameMs = 1000.0 * std::chrono::duration<double>(Clock::now() - now).count();
      if (lastFrame) window.close();
    }
    if (recording && !o->record.empty() && recorded.size() >= 2) {
      saveCameraPath(o->record, recorded);
      std::cout << "recorded " << recorded.size() << " keyframes to " << o->record << "\n";
    }
    std::cout << "viewed on " << window.renderer() << ": " << streamedTotal << " pages streamed\n";
  });
}

}  // namespace vt
