// vt crosscheck TEXTURE: renders named scenes, or frames of a flythrough of an OBJ scene, with the
// CPU oracle (through its public API, <vt/oracle.h>) and with OpenGL from the same cache state and
// compares them pixel by pixel. Writes difference images and summary.json; exits 1 when any pixel
// is mismatched without the oracle's flag.

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/comparison_report.h"
#include "cli/crosscheck_captures.h"
#include "cli/oracle_conversions.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "common/resource_limits.h"
#include "gl/headless_context.h"
#include "render/backend.h"
#include "render/precision_model_file.h"
#include "scene/camera_path.h"
#include "scene/obj_mesh.h"
#include "scene/test_scenes.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

struct Mode {
  const char* name;
  bool exactFilter, trilinear, need8;
};

}  // namespace

void addCrosscheckCommand(CLI::App& app) {
  struct Options {
    std::string texture, scenes = "all", size = "320x200", profile = "auto", output = "crosscheck";
    std::string mesh, path, captures;
    int every = 8;
    unsigned threads = 0;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "crosscheck",
      "Render scenes with the oracle and with OpenGL, or read captures of any renderer, and "
      "compare them pixel by pixel");
  command->add_option("TEXTURE", o->texture, "Virtual-texture file (.vt); not with --captures");
  command
      ->add_option("--captures", o->captures,
                   "Compare the captures of this folder (frames another renderer drew, "
                   "reference/validate-your-renderer.md) with the oracle; writes junit.xml too")
      ->check(CLI::ExistingDirectory);
  command->add_option("--threads", o->threads, "With --captures: oracle threads (0: every core)")
      ->check(workerCount());
  std::string names;
  for (const std::string& name : testSceneNames())
    names.append(names.empty() ? "" : ", ").append(name);
  command->add_option("--scenes", o->scenes, "Comma-separated scene names, or all: " + names)
      ->capture_default_str();
  command->add_option("--mesh", o->mesh, "An OBJ scene flown through along --path instead")
      ->check(CLI::ExistingFile);
  command->add_option("--path", o->path, "Camera path (.json) for --mesh")
      ->check(CLI::ExistingFile);
  command->add_option("--every", o->every, "With --path: every n-th frame")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--size", o->size, "WIDTHxHEIGHT")
      ->check(sizeValidator())
      ->capture_default_str();
  command
      ->add_option("--model,--profile", o->profile,
                   "Precision model the other renderer is judged under: exact, llvmpipe, gl45, or "
                   "a model file (.json); auto follows GL_RENDERER: llvmpipe for llvmpipe with "
                   "FMA, gl45 otherwise")
      ->capture_default_str();
  command->add_option("-o,--output", o->output, "Folder for summary.json and difference images")
      ->capture_default_str();
  command->callback([o] {
    requireOutputFolder(o->output, {o->texture, o->captures, o->mesh, o->path});
    if (!o->captures.empty() && !o->texture.empty())
      throw CLI::ValidationError("TEXTURE", "--captures takes none: each capture names its own");
    // The report goes into a temporary folder that takes the output's place once it is complete
    // (a verdict of mismatched pixels included): a failure leaves the previous report or none.
    TemporaryFolder staging(o->output, "summary.json");
    if (!o->captures.empty()) {
      const CapturesCheckOptions options{o->captures, staging.path(), o->profile, o->threads};
      const bool passed = crosscheckCaptures(options);
      staging.commit();
      if (!passed)
        throw InputError(o->captures,
                         "crosscheck found unexplained pixels or unreadable "
                         "captures (see " +
                             (std::filesystem::path(o->output) / "junit.xml").string() + ")");
      return;
    }
    if (o->texture.empty()) throw CLI::ValidationError("TEXTURE", "needed without --captures");
    RenderSettings settings;
    settings.viewport = parseSize(o->size);
    // The views: frames of a path through a mesh, or the named scenes. Bad input fails here,
    // before any work.
    std::vector<NamedScene> views;
    if (!o->mesh.empty() || !o->path.empty()) {
      if (o->mesh.empty() || o->path.empty())
        throw CLI::ValidationError("--mesh/--path", "a flythrough needs both");
      const Mesh mesh = loadObjMesh(o->mesh);
      const CameraPath path = CameraPath::load(o->path);
      // Each frame drawn in two modes by two renderers.
      requirePathPixelsFit(o->path,
                           static_cast<uint64_t>((path.frameCount() + o->every - 1) / o->every),
                           static_cast<uint64_t>(settings.viewport.width),
                           static_cast<uint64_t>(settings.viewport.height), 4);
      for (int frame = 0; frame < path.frameCount(); frame += o->every) {
        char name[32];
        std::snprintf(name, sizeof name, "frame%04d", frame);
        views.push_back({name, mesh, path.at(frame)});
      }
    } else if (o->scenes == "all") {
      for (const std::string& name : testSceneNames()) views.push_back(testScene(name));
    } else {
      std::stringstream list(o->scenes);
      for (std::string name; std::getline(list, name, ',');) views.push_back(testScene(name));
    }

    // llvmpipe's results depend on these; pin the thread count, record all three.
    ::setenv("LP_NUM_THREADS",
             environment("LP_NUM_THREADS").empty() ? "2" : environment("LP_NUM_THREADS").c_str(),
             1);
    const HeadlessContext context;
    const std::string renderer = context.renderer();
    const PrecisionModel model = resolveModel(o->profile, renderer);
    if (const std::string warning = calibrationMismatch(model, renderer, context.version());
        !warning.empty())
      std::cerr << "vt crosscheck: " << warning << "\n";
    applyModel(settings, model);

    // A model file travels to the oracle's API by its name.
    const std::optional<std::filesystem::path> measured =
        o->profile == "auto" ? measuredModelFile(renderer) : std::nullopt;
    const std::string modelFile = measured ? measured->string()
                                  : o->profile == "auto" || o->profile == "exact" ||
                                          o->profile == "llvmpipe" || o->profile == "gl45"
                                      ? ""
                                      : o->profile;
    const VirtualTextureReader reader(o->texture);
    // Every stored page, or the coarsest levels that fit into an 8192^2 cache texture: uploaded
    // for GL, and the same pages in the same frames prepared for the oracle's API.
    const CacheState cache = cacheOfLevels(reader, -1, 8192);
    const std::unique_ptr<FrameRenderer> gl = makeFrameRenderer(Backend::kGl, cache);
    const oracle::Texture texture = oracle::Texture::open(o->texture);
    const oracle::PreparedCache prepared(texture, publicCacheState(cache));
    const std::filesystem::path folder = staging.path();

    std::vector<Mode> modes = {{"texelfetch-trilinear-need32", true, true, false},
                               {"linear-bilinear-need8", false, false, true}};
    if (!need8Encodes(reader.description().finestLevel()))
      modes.pop_back();  // 8-bit needbuffer limit

    nlohmann::json summary;
    summary["gl_renderer"] = renderer;
    summary["gl_version"] = context.version();
    summary["model"] = settings.model->name;
    summary["texture"] = o->texture;
    summary["resident_pages"] = cache.residentPages.size();
    summary["settings"] = {{"LP_NUM_THREADS", environment("LP_NUM_THREADS")},
                           {"GALLIVM_PERF", environment("GALLIVM_PERF")},
                           {"GALLIUM_OVERRIDE_CPU_CAPS", environment("GALLIUM_OVERRIDE_CPU_CAPS")},
                           {"cpu_fma", static_cast<bool>(__builtin_cpu_supports("fma"))}};
    summary["frames"] = nlohmann::json::array();
    ComparisonTotals totals;
    std::cout << "crosscheck on " << renderer << ", model " << settings.model->name << ", "
              << settings.viewport.width << " x " << settings.viewport.height << "\n";
    for (const NamedScene& scene : views) {
      const std::string& name = scene.name;
      const ClipSpaceMesh mesh = toClipSpace(scene.mesh, scene.camera, settings.viewport);
      const oracle::Scene publicMesh = oracle::publicScene(mesh, settings.viewport);
      for (const Mode& mode : modes) {
        settings.exactFilter = mode.exactFilter;
        settings.trilinear = mode.trilinear;
        settings.need8 = mode.need8;
        const oracle::RenderOptions options = publicRenderOptions(settings, modelFile);
        const oracle::Frame expected = oracle::render(texture, publicMesh, prepared, options);
        const Frame frame = gl->render(mesh, settings);
        const oracle::Comparison c =
            oracle::compare(expected, frame.color, oracle::flatNeed(frame.need));
        writeComparisonImages(folder, name + "-" + mode.name, publicMesh.viewport, c);
        nlohmann::json record = {{"scene", name}, {"mode", mode.name}};
        record.update(comparisonJson(c));
        summary["frames"].push_back(record);
        totals.add(c);
        printComparison(name, mode.name, c);
      }
    }
    summary["totals"] = totals.json();
    summary["passed"] = totals.unexplained == 0;
    writeFileAtomically(folder / "summary.json", summary.dump(2) + "\n");
    staging.commit();
    std::printf("crosscheck: %s: %s\n", totals.line().c_str(),
                totals.unexplained == 0 ? "passed" : "FAILED");
    std::fflush(stdout);
    if (totals.unexplained != 0)
      throw InputError(o->texture,
                       "crosscheck found unexplained pixels (see " +
                           (std::filesystem::path(o->output) / "summary.json").string() + ")");
  });
}

}  // namespace vt
