// vt-capture: the GPU side of a split check. It draws with the GL path only and writes what it
// drew; judging runs elsewhere, where the oracle is installed (`vt calibrate --probes`, `vt
// crosscheck --captures`). Links no image library, Embree, TBB or libzip, and the C++ runtime
// statically, so that it runs on a bare machine with an OpenGL driver (scripts/gpu-kit.sh).
//
//   vt-capture probes REQUESTS -o OUT      the calibration's probe draws (capture/probe_files.h)
//   vt-capture scenes TEXTURE ... -o OUT   captures of the named scenes or of a flythrough
//   vt-capture timings TEXTURE ... -o FILE frame times of the same views at several sizes
//   vt-capture flight TEXTURE --mesh OBJ --path PATH -o OUT   a flight streaming into the GL cache,
//                                          every n-th frame a capture (capture/streamed_flight.h)
//
// Exit codes: 0 success, 1 bad input or a failed operation (one line on stderr naming the file and
// the problem), 2 bad arguments (the error and the usage line on stderr).

#include <epoxy/gl.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "capture/capture_writer.h"
#include "capture/probe_files.h"
#include "capture/streamed_flight.h"
#include "capture/sweep_files.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/json_text.h"
#include "common/posix_file.h"
#include "format/virtual_texture_reader.h"
#include "gl/gl_frame_renderer.h"
#include "gl/headless_context.h"
#include "render/cache_state.h"
#include "render/check_modes.h"
#include "runtime/heuristic.h"
#include "scene/camera_path.h"
#include "scene/obj_mesh.h"
#include "scene/test_scenes.h"

namespace vt::capture {
namespace {

// llvmpipe's results depend on its thread count: pinned to 2 unless set (as vt crosscheck does).
void pinLlvmpipeThreads() { ::setenv("LP_NUM_THREADS", "2", 0); }

struct ViewOptions {
  std::string texture, scenes = "all", mesh, path;
  int every = 8;
  std::string size = "320x200";
};

void addViewOptions(CLI::App* command, ViewOptions& o) {
  command->add_option("texture", o.texture, "Virtual-texture file (.vt)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--scenes", o.scenes, "Comma-separated scene names, or all")
      ->capture_default_str();
  command->add_option("--mesh", o.mesh, "An OBJ scene flown through along --path instead")
      ->check(CLI::ExistingFile);
  command->add_option("--path", o.path, "Camera path (.json) for --mesh")->check(CLI::ExistingFile);
  command->add_option("--every", o.every, "With --path: every n-th frame")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
}

std::vector<NamedScene> views(const ViewOptions& o) {
  if (o.mesh.empty() != o.path.empty())
    throw CLI::ValidationError("--mesh", "--mesh and --path go together");
  if (o.mesh.empty()) return namedSceneViews(o.scenes);
  return flythroughViews(loadObjMesh(o.mesh), CameraPath::load(o.path), o.every);
}

// Calls `draw(view, mesh, mode, settings)` for every view in every mode at `viewport`.
template <typename Draw>
void forEachDraw(const std::vector<NamedScene>& list, Viewport viewport, uint32_t finestLevel,
                 Draw&& draw) {
  for (const NamedScene& view : list) {
    const ClipSpaceMesh mesh = toClipSpace(view.mesh, view.camera, viewport);
    for (const CheckMode& mode : checkModes(finestLevel)) {
      RenderSettings settings;
      settings.viewport = viewport;
      applyMode(settings, mode);
      draw(view, mesh, mode, settings);
    }
  }
}

void probes(const std::string& requests, const std::string& output) {
  const size_t count = countProbeRequests(requests);
  if (count == 0) throw InputError(requests, "holds no probe request (probe-0000.json)");
  TemporaryFolder::requireReplaceable(output, "probes.json");
  const HeadlessContext context;
  TemporaryFolder staging(output, "probes.json");
  for (size_t i = 0; i < count; ++i) {
    const ProbeRequest request = readProbeRequest(requests, i);
    writeProbeRequest(staging.path(), i, request);
    writeProbeResult(staging.path(), i, request, drawHere(request));
  }
  // The probe pack's sweeps, where the requests ask for them (capture/sweep_files.h).
  const std::vector<calibrate::FunctionSweep> sweeps = readSweepRequests(requests);
  uint64_t swept = 0;
  for (const calibrate::FunctionSweep& sweep : sweeps) {
    writeSweepResult(staging.path(), sweep, calibrate::drawFunctionSweepHere(sweep));
    swept += sweep.count;
  }
  if (!sweeps.empty()) writeSweepRequests(staging.path(), sweeps);
  writeProbeFolder(staging.path(), {count, calibrate::identityHere()});
  staging.commit();
  std::cout << "vt-capture: drew " << count << " probe draws and " << sweeps.size() << " sweeps of "
            << swept << " inputs on " << context.renderer() << ": wrote " << output << "\n";
}

void scenes(const ViewOptions& o, const std::string& textureName, const std::string& output) {
  const std::vector<NamedScene> list = views(o);
  TemporaryFolder::requireReplaceable(output, "captures.summary");
  const Viewport viewport = parseSize(o.size);
  const HeadlessContext context;
  const VirtualTextureReader reader(o.texture);
  const CacheState cache = cacheOfLevels(reader, -1, 8192);
  GlFrameRenderer gl(cache);
  TemporaryFolder staging(output, "captures.summary");
  const std::string file =
      textureName.empty() ? std::filesystem::absolute(o.texture).string() : textureName;
  nlohmann::ordered_json manifests = nlohmann::ordered_json::array();
  forEachDraw(list, viewport, reader.description().finestLevel(),
              [&](const NamedScene& view, const ClipSpaceMesh& mesh, const CheckMode& mode,
                  const RenderSettings& settings) {
                const Frame frame = gl.render(mesh, settings);
                const std::string name = view.name + "-" + mode.name + ".json";
                writeCapturedFrame(staging.path() / name,
                                   {context.renderer(), file, reader.identity(), &mesh, &cache,
                                    mode.need8, mode.trilinear, mode.exactFilter, &frame,
                                    nlohmann::json{{"gl_version", context.version()}}});
                manifests.push_back(name);
              });
  const nlohmann::ordered_json summary = {
      {"renderer", context.renderer()}, {"gl_version", context.version()}, {"captures", manifests}};
  writeFileAtomically(staging.path() / "captures.summary", summary.dump(1) + "\n");
  staging.commit();
  std::cout << "vt-capture: " << manifests.size() << " captures on " << context.renderer()
            << ": wrote " << output << "\n";
}

// The median of `values` (sorted in place).
double median(std::vector<double>& values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

void timings(const ViewOptions& o, const std::vector<std::string>& sizes, int repeats,
             const std::string& output) {
  const std::vector<NamedScene> list = views(o);
  const HeadlessContext context;
  const VirtualTextureReader reader(o.texture);
  const CacheState cache = cacheOfLevels(reader, -1, 8192);
  GlFrameRenderer gl(cache);
  GLuint query = 0;
  glGenQueries(1, &query);
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const std::string& size : sizes) {
    const Viewport viewport = parseSize(size);
    forEachDraw(list, viewport, reader.description().finestLevel(),
                [&](const NamedScene& view, const ClipSpaceMesh& mesh, const CheckMode& mode,
                    const RenderSettings& settings) {
                  gl.draw(mesh, settings);  // warm-up: shaders compiled, targets allocated
                  std::vector<double> gpu, wall;
                  for (int r = 0; r < repeats; ++r) {
                    const auto start = std::chrono::steady_clock::now();
                    glBeginQuery(GL_TIME_ELAPSED, query);
                    gl.draw(mesh, settings);  // uploads the mesh, draws, glFinish
                    glEndQuery(GL_TIME_ELAPSED);
                    GLuint64 nanoseconds = 0;
                    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &nanoseconds);
                    wall.push_back(std::chrono::duration<double, std::milli>(
                                       std::chrono::steady_clock::now() - start)
                                       .count());
                    gpu.push_back(static_cast<double>(nanoseconds) / 1e6);
                  }
                  const double gpuMedian = median(gpu), wallMedian = median(wall);
                  rows.push_back({{"size", size},
                                  {"view", view.name},
                                  {"mode", mode.name},
                                  {"gpu_ms_median", gpuMedian},
                                  {"gpu_ms_min", gpu.front()},
                                  {"gpu_ms_max", gpu.back()},
                                  {"wall_ms_median", wallMedian},
                                  {"wall_ms_min", wall.front()},
                                  {"wall_ms_max", wall.back()}});
                  std::cout << size << " " << view.name << " " << mode.name << ": GPU " << gpuMedian
                            << " ms, wall " << wallMedian << " ms (median of " << repeats << ")\n";
                });
  }
  glDeleteQueries(1, &query);
  const nlohmann::ordered_json report = {{"renderer", context.renderer()},
                                         {"gl_version", context.version()},
                                         {"repeats", repeats},
                                         {"what",
                                          "GL_TIME_ELAPSED and wall time of one draw "
                                          "(mesh upload, draw, glFinish; no readback)"},
                                         {"frames", rows}};
  writeFileAtomically(output, report.dump(1) + "\n");
}

struct FlightArguments {
  std::string texture, mesh, path, size = "320x200", output;
  StreamedFlightOptions options;
};

CLI::App* addFlightCommand(CLI::App& app, FlightArguments& a) {
  CLI::App* command = app.add_subcommand(
      "flight", "Fly a camera path streaming pages into the GL cache; every n-th frame a capture");
  command->add_option("texture", a.texture, "Virtual-texture file (.vt)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--mesh", a.mesh, "OBJ mesh with virtual texture coordinates")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--path", a.path, "Camera path (.json)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--size", a.size, "WIDTHxHEIGHT")
      ->check(vt::sizeValidator())
      ->capture_default_str();
  StreamedFlightOptions& o = a.options;
  command
      ->add_option("--heuristic", o.heuristic, "Page priority (pixelsum, pixelsum*distance, ...)")
      ->check(CLI::Validator(
          [](std::string& text) {
            try {
              vt::Heuristic::parse(text);
              return std::string();
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
          },
          "HEURISTIC"))
      ->capture_default_str();
  command->add_option("--budget", o.budget, "Pages streamed a frame")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();
  command->add_option("--cache-frames", o.cacheFrames, "The cache holds N x N page frames")
      ->check(CLI::Range(2, 1024))
      ->capture_default_str();
  command->add_option("--initial-levels", o.initialLevels, "Levels 0..K-1 loaded first")
      ->check(CLI::Range(0, 32))
      ->capture_default_str();
  command->add_option("--every", o.every, "Capture every n-th frame")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_flag("--async-readback", o.asyncReadback,
                    "Analyse each frame's needbuffer one frame late (pixel-buffer objects)");
  command->add_flag("--linear", o.linear,
                    "Sample with GL_LINEAR into an 8-bit needbuffer (default: texel fetches, "
                    "manual trilinear, 32-bit needbuffer)");
  command->add_option("--texture-name", o.textureName,
                      "The texture's path as the manifests name it (default: absolute)");
  command->add_option("-o,--output", a.output, "Folder for the captures and flight.summary")
      ->required();
  return command;
}

void flight(FlightArguments a) {
  TemporaryFolder::requireReplaceable(a.output, "flight.summary");
  const VirtualTextureReader reader(a.texture);
  const Mesh mesh = loadObjMesh(a.mesh);
  const CameraPath path = CameraPath::load(a.path);
  a.options.viewport = parseSize(a.size);
  const HeadlessContext context;
  TemporaryFolder staging(a.output, "flight.summary");
  const StreamedFlight flown =
      flyAndCapture(reader, mesh, path, a.options, context.renderer(), staging.path());
  staging.commit();
  std::cout << "vt-capture: flew " << flown.frames << " frames on " << context.renderer() << " ("
            << flown.streamed << " pages streamed, " << flown.misses
            << " needed pages missed): " << flown.captures << " captures in " << a.output << "\n";
}

}  // namespace
}  // namespace vt::capture

int main(int argc, char** argv) {
  using namespace vt::capture;
  CLI::App app(
      "vt-capture: draw with OpenGL what `vt` judges elsewhere (probes, captures, frame "
      "times)",
      "vt-capture");
  app.require_subcommand(1);

  std::string requests, output;
  CLI::App* probesCommand =
      app.add_subcommand("probes",
                         "Draw the calibration's probe requests (vt calibrate "
                         "--record-probes) and write their results");
  probesCommand->add_option("requests", requests, "Folder of probe requests")
      ->required()
      ->check(CLI::ExistingDirectory);
  probesCommand->add_option("-o,--output", output, "Folder for the drawn probes")->required();

  ViewOptions sceneOptions;
  std::string textureName;
  CLI::App* scenesCommand =
      app.add_subcommand("scenes", "Capture the named scenes or a flythrough in both modes");
  addViewOptions(scenesCommand, sceneOptions);
  scenesCommand->add_option("--size", sceneOptions.size, "WIDTHxHEIGHT")
      ->check(vt::sizeValidator())
      ->capture_default_str();
  scenesCommand->add_option("--texture-name", textureName,
                            "The texture's path as the manifests name it (default: absolute)");
  scenesCommand->add_option("-o,--output", output, "Folder for the captures")->required();

  ViewOptions timingOptions;
  std::vector<std::string> sizes = {"1280x720", "1920x1080"};
  int repeats = 5;
  CLI::App* timingsCommand =
      app.add_subcommand("timings", "Time the draws of the same views at several sizes");
  addViewOptions(timingsCommand, timingOptions);
  timingsCommand->add_option("--sizes", sizes, "WIDTHxHEIGHT, comma-separated")
      ->delimiter(',')
      ->check(vt::sizeValidator())
      ->capture_default_str();
  timingsCommand->add_option("--repeats", repeats, "Draws timed per view and mode")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  timingsCommand->add_option("-o,--output", output, "JSON file for the timings")->required();

  FlightArguments flightArguments;
  CLI::App* flightCommand = addFlightCommand(app, flightArguments);

  try {
    app.parse(argc, argv);
    pinLlvmpipeThreads();
    if (*flightCommand) flight(flightArguments);
    if (*probesCommand) probes(requests, output);
    if (*scenesCommand) scenes(sceneOptions, textureName, output);
    if (*timingsCommand) timings(timingOptions, sizes, repeats, output);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    const CLI::App* command = app.get_subcommands().empty() ? &app : app.get_subcommands().front();
    std::cerr << "vt-capture: " << e.what() << "\n"
              << CLI::Formatter().make_usage(
                     command, command == &app ? "vt-capture" : "vt-capture " + command->get_name());
    return 2;
  } catch (const vt::InputError& e) {
    std::cerr << "vt-capture: " << e.what() << "\n";
    return 1;
  } catch (const nlohmann::json::exception& e) {
    std::cerr << "vt-capture: " << vt::jsonErrorText(e) << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "vt-capture: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
