#include "viewer/interactive_flight.h"

#include <epoxy/gl.h>
// GLFW after epoxy, without its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "common/image_file.h"
#include "eval/flight_run.h"
#include "eval/frame_drawer.h"
#include "eval/frame_plan.h"
#include "gl/gl_frame_renderer.h"
#include "gl/hud_overlay.h"
#include "gl/hud_text.h"
#include "render/frame_images.h"
#include "runtime/needbuffer_scale.h"
#include "scene/fly_camera.h"
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

// The HUD's four lines: the frame and its time, the pages needed and missing, those requested
// and streamed (and streamed in all), and the cache's fill.
std::vector<std::string> hudLines(int frame, double frameMs, bool recording,
                                  const FrameStatistics& statistics, uint64_t streamedTotal,
                                  uint32_t capacity) {
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
  std::snprintf(lines[3], sizeof lines[3], "RESIDENT %llu / %u  %.0f%%",
                static_cast<unsigned long long>(statistics.resident), capacity,
                100.0 * static_cast<double>(statistics.resident) / capacity);
  return {lines[0], lines[1], lines[2], lines[3]};
}

// The window's back buffer as an image file.
void writeScreenshot(glm::ivec2 windowSize, const std::filesystem::path& file) {
  Frame shot;  // rows bottom to top, as GL reads them
  shot.viewport = {windowSize.x, windowSize.y};
  shot.color.resize(size_t(windowSize.x) * size_t(windowSize.y) * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);  // the window's, not the renderer's target
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, windowSize.x, windowSize.y, GL_RGBA, GL_UNSIGNED_BYTE, shot.color.data());
  const std::vector<uint8_t> rows = colorImage(shot);
  writeImage8(file, static_cast<uint32_t>(windowSize.x), static_cast<uint32_t>(windowSize.y), 4,
              std::as_bytes(std::span(rows)));
}

}  // namespace

void flyInteractively(WindowContext& window, const VirtualTextureReader& reader,
                      const InteractiveFlight& request, std::ostream& out) {
  const FlightConfiguration& configuration = request.configuration;
  Camera camera = request.path ? request.path->at(0) : request.start;
  FlightOptions flight;
  flight.settings.need8 = need8Encodes(reader.description().finestLevel());
  flight.threadedStreaming = true;
  flight.link = request.link;
  const glm::ivec2 opened = window.framebufferSize();
  const Viewport size{std::max(1, opened.x), std::max(1, opened.y)};
  FlightRun run(reader, configuration, flight, reducedViewport(size, configuration.needScaleLog2),
                initialPages(reader, configuration, {}, flight.settings.need8));
  GlFrameRenderer gl(run.runtime().cacheState());
  FrameDrawer drawer(request.mesh, flight.settings, gl);
  DrawnPasses drawn;
  HudOverlay hud;
  std::vector<Keyframe> recorded;
  bool recording = request.recordFromStart;
  // Writes the recording when it ends, if it holds a path (two keyframes or more).
  const auto saveRecording = [&] {
    if (request.record.empty() || recorded.size() < 2) return;
    saveCameraPath(request.record, recorded);
    out << "recorded " << recorded.size() << " keyframes to " << request.record.string() << "\n";
  };
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
      if (!recording) saveRecording();
    }
    beforePrevious = previous;
    previous = camera;
    if (request.path) {
      camera = request.path->at(frame);
    } else {
      const float fast = window.keyDown(GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.0f;
      camera = flyCamera(camera, readInput(window, cursor), seconds,
                         static_cast<float>(request.speed) * fast);
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
    const uint32_t side = cacheFramesFor(configuration, reader.description());
    hud.draw(renderHudText(
                 hudLines(frame, frameMs, recording, statistics, streamedTotal, side * side), 2),
             windowSize);

    const bool lastFrame = request.maxFrames > 0 && frame + 1 >= request.maxFrames;
    if (lastFrame && !request.screenshot.empty()) writeScreenshot(windowSize, request.screenshot);
    window.swapAndPoll();
    frameMs = 1000.0 * std::chrono::duration<double>(Clock::now() - now).count();
    if (lastFrame) window.close();
  }
  if (recording) saveRecording();
  out << "viewed on " << window.renderer() << ": " << streamedTotal << " pages streamed\n";
}

}  // namespace vt
