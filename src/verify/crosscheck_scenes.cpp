#include "verify/crosscheck_scenes.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "calibrate/fingerprint.h"
#include "common/posix_file.h"
#include "format/virtual_texture_reader.h"
#include "gl/headless_context.h"
#include "render/arithmetic_points.h"
#include "backends/backend.h"
#include "render/check_modes.h"
#include "render/precision_model.h"
#include "render/precision_model_file.h"
#include "scene/clip_space_mesh.h"
#include "shader/needbuffer.h"
#include "verify/oracle_conversions.h"

namespace vt {
namespace {

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

// The model file handed to the oracle's API by its name: a measured model that auto chose, or
// the file named; none for the shipped models, which travel as a profile.
std::string modelFileFor(const std::string& option, const PrecisionModel& chosen,
                         const std::string& renderer) {
  if (option == "auto") {
    if (isModelName(chosen.name)) return "";
    const std::optional<std::filesystem::path> measured = measuredModelFile(renderer);
    return measured ? measured->string() : "";
  }
  return isModelName(option) ? "" : option;
}

}  // namespace

ScenesCheck crosscheckScenes(const ScenesCheckOptions& options) {
  TemporaryFolder staging(options.output, "summary.json");
  const std::filesystem::path& folder = staging.path();
  ::setenv("LP_NUM_THREADS",
           environment("LP_NUM_THREADS").empty() ? "2" : environment("LP_NUM_THREADS").c_str(), 1);
  const HeadlessContext context;
  ScenesCheck check{context.renderer(), context.version(), "", {}};
  RenderSettings settings;
  settings.viewport = options.viewport;
  // auto: a pinned model only where its fingerprint reproduces here (calibrate/fingerprint.h).
  std::string note;
  const PrecisionModel model =
      calibrate::resolveModelHere(options.model, check.renderer, &note);
  if (!note.empty()) std::cerr << "vt crosscheck: " << note << "\n";
  if (const std::string warning = calibrationMismatch(model, check.renderer, check.version);
      !warning.empty())
    std::cerr << "vt crosscheck: " << warning << "\n";
  applyModel(settings, model);
  check.model = settings.model->name;
  const std::string modelFile = modelFileFor(options.model, model, check.renderer);

  const VirtualTextureReader reader(options.texture);
  // Uploaded for GL, and the same pages in the same frames prepared for the oracle's API.
  const CacheState cache = cacheOfLevels(reader, -1, 8192);
  const std::unique_ptr<FrameRenderer> gl = makeFrameRenderer(Backend::kGl, cache);
  const oracle::Texture texture = oracle::Texture::open(options.texture);
  const oracle::PreparedCache prepared(texture, publicCacheState(cache));

  const std::vector<CheckMode> modes = checkModes(reader.description().finestLevel());

  nlohmann::json summary;
  summary["gl_renderer"] = check.renderer;
  summary["gl_version"] = check.version;
  summary["model"] = check.model;
  summary["texture"] = options.texture.string();
  summary["resident_pages"] = cache.residentPages.size();
  summary["settings"] = {{"LP_NUM_THREADS", environment("LP_NUM_THREADS")},
                         {"GALLIVM_PERF", environment("GALLIVM_PERF")},
                         {"LP_PERF", environment("LP_PERF")},
                         {"GALLIUM_OVERRIDE_CPU_CAPS", environment("GALLIUM_OVERRIDE_CPU_CAPS")},
                         {"cpu_fma", static_cast<bool>(__builtin_cpu_supports("fma"))}};
  summary["frames"] = nlohmann::json::array();
  std::cout << "crosscheck on " << check.renderer << ", model " << check.model << ", "
            << settings.viewport.width << " x " << settings.viewport.height << "\n";
  for (const NamedScene& scene : options.views) {
    const ClipSpaceMesh mesh = toClipSpace(scene.mesh, scene.camera, settings.viewport);
    const oracle::Scene publicMesh = oracle::publicScene(mesh, settings.viewport);
    for (const CheckMode& mode : modes) {
      applyMode(settings, mode);
      // GL draws first: the oracle then builds result sets only where GL's frame differs.
      const Frame frame = gl->render(mesh, settings);
      const std::vector<uint32_t> need = oracle::flatNeed(frame.need);
      oracle::RenderOptions renderOptions = publicRenderOptions(settings, modelFile);
      if (!options.allSets) {
        renderOptions.judgedColor = frame.color;
        renderOptions.judgedNeed = need;
      }
      const oracle::Frame expected = oracle::render(texture, publicMesh, prepared, renderOptions);
      const oracle::Comparison c = oracle::compare(expected, frame.color, need);
      const SetWidths widths = verdictWidths(expected);
      writeComparisonImages(folder, scene.name + "-" + mode.name, publicMesh.viewport, c);
      nlohmann::json record = {{"scene", scene.name}, {"mode", mode.name}};
      record.update(comparisonJson(c, widths));
      summary["frames"].push_back(record);
      check.totals.add(c, widths);
      printComparison(scene.name, mode.name, c, widths);
    }
  }
  summary["totals"] = check.totals.json();
  summary["passed"] = check.passed();
  writeFileAtomically(folder / "summary.json", summary.dump(2) + "\n");
  staging.commit();
  std::printf("crosscheck: %s: %s\n", check.totals.line().c_str(),
              check.passed() ? "passed" : "FAILED");
  std::fflush(stdout);
  return check;
}

}  // namespace vt
