// vt eval TEXTURE: chapter 4's comparison. Flies configurations of the streaming system over one
// camera path, measures each frame against the reference image (every needed page resident),
// runs independent configurations in parallel and writes frames.csv, summary.md/.json and plots
// (eval/evaluation_report.h).
//
// Configurations come from a JSON file (--configs: { "defaults": {...}, "configurations":
// [{...}, ...], "figures": [{ "file": "basic.png", "title": "...", "measure": "ssim", "runs":
// ["name", ...] }] } in eval/flight_configuration.h's form; names must differ) or are the product
// of comma-separated lists: heuristic x budget x ancestors x locked levels x needbuffer scale x
// lookahead.

#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/json_text.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "common/progress_bar.h"
#include "common/resource_limits.h"
#include "eval/evaluation.h"
#include "eval/evaluation_report.h"
#include "eval/flight_records.h"
#include "runtime/needbuffer_scale.h"
#include "scene/box_room.h"
#include "scene/obj_mesh.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');)
    if (!item.empty()) items.push_back(item);
  if (items.empty()) throw std::invalid_argument("empty list '" + text + "'");
  return items;
}

struct ConfigurationsFile {
  std::vector<FlightConfiguration> configurations;
  std::vector<EvaluationFigure> figures;
};

// Figures name runs by label; everything is checked before the first frame is flown.
EvaluationFigure figureOf(const nlohmann::json& entry,
                          const std::vector<FlightConfiguration>& configurations) {
  EvaluationFigure figure;
  figure.file = entry.at("file").get<std::string>();
  figure.title = entry.value("title", figure.file);
  figure.measure = entry.value("measure", "ssim");
  if (figure.file.find('/') != std::string::npos || !figure.file.ends_with(".png"))
    throw std::invalid_argument("figure '" + figure.file + "': the file must be a plain name.png");
  if (figure.measure != "ssim" && figure.measure != "wssim" && figure.measure != "rmse")
    throw std::invalid_argument("figure '" + figure.file + "': measure '" + figure.measure +
                                "' is not ssim, wssim or rmse");
  for (const auto& run : entry.at("runs")) {
    const std::string label = run.get<std::string>();
    if (std::none_of(configurations.begin(), configurations.end(),
                     [&](const FlightConfiguration& c) { return c.label() == label; }))
      throw std::invalid_argument("figure '" + figure.file + "': no configuration named '" + label +
                                  "'");
    figure.runs.push_back(label);
  }
  return figure;
}

ConfigurationsFile loadConfigurations(const std::filesystem::path& file) {
  try {
    const nlohmann::json root = readJsonFile(file, "configurations");
    FlightConfiguration defaults;
    const nlohmann::json* list = &root;
    if (root.is_object()) {
      if (root.contains("defaults"))
        defaults = FlightConfiguration::fromJson(root["defaults"], FlightConfiguration{});
      list = &root.at("configurations");
    }
    if (!list->is_array() || list->empty())
      throw std::invalid_argument("expected a non-empty list of configurations");
    ConfigurationsFile result;
    std::set<std::string> labels;
    for (size_t c = 0; c < list->size(); ++c) {
      try {
        result.configurations.push_back(FlightConfiguration::fromJson((*list)[c], defaults));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("configuration " + std::to_string(c + 1) + ": " + e.what());
      }
      if (!labels.insert(result.configurations.back().label()).second)
        throw std::invalid_argument("configuration " + std::to_string(c + 1) + ": the name '" +
                                    result.configurations.back().label() + "' is taken");
    }
    if (root.is_object() && root.contains("figures"))
      for (const auto& entry : root["figures"])
        result.figures.push_back(figureOf(entry, result.configurations));
    return result;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "not a configurations file: " + jsonErrorText(e));
  } catch (const std::invalid_argument& e) {
    throw InputError(file, e.what());
  }
}

}  // namespace

void addEvalCommand(CLI::App& app) {
  struct Options {
    FlightSceneArguments scene;
    std::string configs, output = "eval", title;
    std::string heuristics = "pixelsum", budgets = "5,10", ancestors = "none", locked = "0",
                needScales = "1", lookAheads = "none", hotSpot = "shifted", profile = "exact",
                parents = "off";
    uint32_t cacheFrames = 16, initialLevels = 3;
    bool preloadVisible = false, noiseSkipping = false;
    unsigned jobs = 0;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "eval", "Compare streaming configurations over a camera path against reference images");
  o->scene.addTo(command);
  command->add_option("--configs", o->configs,
                      "Configurations (.json); otherwise the product of the lists below");
  command->add_option("--heuristic", o->heuristics, "Heuristics, comma-separated")
      ->check(heuristicArgument(true))
      ->capture_default_str();
  command->add_option("--budget", o->budgets, "Pages per frame, comma-separated")
      ->check(wholeNumbersIn(0, 1 << 20))
      ->capture_default_str();
  command
      ->add_option("--ancestors", o->ancestors,
                   joinedNames(kAncestorStrategyNames) + "; comma-separated")
      ->capture_default_str();
  command->add_option("--locked-levels", o->locked, "Locked levels, comma-separated")
      ->check(wholeNumbersIn(0, 24))
      ->capture_default_str();
  command
      ->add_option("--need-scale", o->needScales,
                   "Needbuffer scales " + joinedNames(kNeedScaleNames) + "; comma-separated")
      ->capture_default_str();
  command
      ->add_option("--lookahead", o->lookAheads, joinedNames(kLookAheadNames) + "; comma-separated")
      ->capture_default_str();
  command
      ->add_option("--trilinear-parents", o->parents,
                   "off, on: whether a needed page's parent counts as needed; comma-separated")
      ->capture_default_str();
  command->add_option("--hotspot", o->hotSpot, "HotSpot centre: " + joinedNames(kHotSpotModeNames))
      ->capture_default_str();
  command->add_flag("--noise-skipping", o->noiseSkipping, "NoiseValueSkipping (with extern)");
  command->add_option("--cache-frames", o->cacheFrames, "The cache holds N x N frames")
      ->check(wholeNumbersIn(1, 256))
      ->capture_default_str();
  command->add_option("--initial-levels", o->initialLevels, "Levels 0..K-1 loaded first")
      ->check(wholeNumbersIn(0, 24))
      ->capture_default_str();
  command->add_flag("--preload-visible", o->preloadVisible,
                    "Also load the pages the first frame needs before it (4.2.1)");
  command->add_option("--profile", o->profile, "Precision profile of the oracle")
      ->check(CLI::IsMember({"exact", "llvmpipe"}))
      ->capture_default_str();
  command->add_option("--jobs", o->jobs, "Runs at once (0: every core)")
      ->check(workerCount())
      ->capture_default_str();
  command->add_option("--title", o->title, "Title of the summary and plots");
  command->add_option("-o,--output", o->output, "Output folder")->capture_default_str();
  command->callback([o, command] {
    const VirtualTextureReader reader(o->scene.texture);
    const CameraPath path = o->scene.cameraPath();
    const Mesh mesh = o->scene.loadMesh();

    std::vector<FlightConfiguration> configurations;
    std::vector<EvaluationFigure> figures;
    if (!o->configs.empty()) {
      for (const char* list : {"--heuristic", "--budget", "--ancestors", "--locked-levels",
                               "--need-scale", "--lookahead", "--trilinear-parents"})
        if (command->count(list) > 0)
          throw std::invalid_argument(std::string("give either --configs or ") + list);
      ConfigurationsFile loaded = loadConfigurations(o->configs);
      configurations = std::move(loaded.configurations);
      figures = std::move(loaded.figures);
    } else {
      FlightConfiguration base;
      base.hotSpot = parseHotSpotMode(o->hotSpot);
      base.noiseSkipping = o->noiseSkipping;
      base.cacheFrames = o->cacheFrames;
      base.initialLevels = o->initialLevels;
      base.preloadVisible = o->preloadVisible;
      for (const std::string& heuristic : splitList(o->heuristics))
        for (const std::string& budget : splitList(o->budgets))
          for (const std::string& ancestors : splitList(o->ancestors))
            for (const std::string& locked : splitList(o->locked))
              for (const std::string& scale : splitList(o->needScales))
                for (const std::string& lookAhead : splitList(o->lookAheads))
                  for (const std::string& parents : splitList(o->parents)) {
                    if (parents != "off" && parents != "on")
                      throw std::invalid_argument("--trilinear-parents takes off and on, not '" +
                                                  parents + "'");
                    nlohmann::json settings = {{"heuristic", heuristic},
                                               {"ancestors", ancestors},
                                               {"lookahead", lookAhead},
                                               {"trilinear_parents", parents == "on"}};
                    try {
                      settings["budget"] = std::stoll(budget);
                      settings["locked_levels"] = std::stoll(locked);
                      settings["need_scale"] = std::stoll(scale);
                    } catch (const std::exception&) {
                      throw std::invalid_argument("not a whole number in '" + budget + "', '" +
                                                  locked + "' or '" + scale + "'");
                    }
                    configurations.push_back(FlightConfiguration::fromJson(settings, base));
                  }
    }

    // The results replace the output folder: refuse one with other files before flying.
    std::vector<std::filesystem::path> inputs = o->scene.inputs();
    inputs.push_back(o->configs);
    requireOutputFolder(o->output, inputs);
    TemporaryFolder::requireReplaceable(o->output, "summary.json");
    EvaluationOptions options;
    options.settings.viewport = parseSize(o->scene.size);
    // The reference images are kept for every frame: refused before the first is drawn.
    const Viewport& v = options.settings.viewport;
    const uint64_t referenceBytes =
        static_cast<uint64_t>(path.frameCount()) * static_cast<uint64_t>(v.width) * v.height * 4;
    if (referenceBytes > kMaxReferenceImageBytes)
      throw limitError(o->scene.path.empty() ? "the box room's path" : o->scene.path,
                       "keeping a " + std::to_string(v.width) + " x " + std::to_string(v.height) +
                           " reference image for each of its " + std::to_string(path.frameCount()) +
                           " frames",
                       referenceBytes, kMaxReferenceImageBytes, " bytes");
    // The reference run and one run per configuration, each drawing every frame.
    requirePathPixelsFit(o->scene.path.empty() ? "the box room's path" : o->scene.path,
                         static_cast<uint64_t>(path.frameCount()), static_cast<uint64_t>(v.width),
                         static_cast<uint64_t>(v.height), 1 + configurations.size());
    options.settings.need8 = need8Encodes(reader.description().finestLevel());
    options.settings.profile = reference::parsePrecisionProfile(o->profile);
    options.jobs = o->jobs;
    const uint64_t total = static_cast<uint64_t>(path.frameCount()) * (1 + configurations.size());
    ProgressBar bar("eval", total);
    options.progress = [&bar](uint64_t done, uint64_t) { bar.update(done); };
    const Evaluation evaluation = evaluate(reader, mesh, path, configurations, options);

    EvaluationDescription description;
    description.title =
        o->title.empty() ? std::filesystem::path(o->scene.texture).stem().string() : o->title;
    description.scene = o->scene.sceneName();
    description.texture = o->scene.texture;
    description.figures = figures;
    description.jobs = o->jobs ? o->jobs : std::max(1u, std::thread::hardware_concurrency());
    writeEvaluation(o->output, description, path, options.settings, evaluation);
    std::cout << "evaluated " << configurations.size() << " configurations over "
              << path.frameCount() << " frames in " << evaluation.wallSeconds
              << " s (reference images " << evaluation.referenceSeconds << " s); wrote "
              << (std::filesystem::path(o->output) / "summary.md").string() << "\n";
    for (const EvaluationRun& run : evaluation.runs) {
      const nlohmann::json totals = flightTotals(run.result);
      std::cout << "  " << run.configuration.label() << ": mean SSIM "
                << totals["mean_ssim"].get<double>() << ", min SSIM "
                << totals["min_ssim"].get<double>() << ", mean RMSE "
                << totals["mean_rmse"].get<double>() << ", " << run.result.totals.streamed
                << " pages streamed, " << run.result.seconds << " s\n";
    }
  });
}

}  // namespace vt
