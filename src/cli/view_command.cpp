// vt view TEXTURE: parses the options of an interactive flight (viewer/interactive_flight.h),
// opens the window and flies in it. Keys: W A S D to move, Q E down and up, the left mouse button
// held to look, Shift to go fast, R to start and stop recording the camera path (written with
// --record), Escape to quit. --frames, --screenshot, --path and --recording let scripts and tests
// drive it.

#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/output_path.h"
#include "gl/window_context.h"
#include "scene/box_room.h"
#include "scene/camera_path.h"
#include "scene/obj_mesh.h"
#include "viewer/interactive_flight.h"

namespace vt {
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
    InteractiveFlight request{
        .mesh = o->mesh.empty() ? boxRoom() : loadObjMesh(o->mesh),
        .start = o->camera.empty() ? boxRoomCamera() : parseCamera(o->camera),
        .path = o->path.empty() ? std::nullopt : std::optional(CameraPath::load(o->path)),
        .configuration = configurationOptions->configuration(),
        .link = {o->linkLatency, o->linkMegabytes * 1e6},
        .speed = o->speed,
        .maxFrames = o->maxFrames,
        .recordFromStart = o->recordFromStart,
        .record = o->record,
        .screenshot = o->screenshot};
    const Viewport size = parseSize(o->size);
    WindowContext window(size.width, size.height, "vt view: " + o->texture);
    flyInteractively(window, reader, request, std::cout);
  });
}

}  // namespace vt
