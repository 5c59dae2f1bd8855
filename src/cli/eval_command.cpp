// vt eval TEXTURE: chapter 4's comparison. Flies configurations of the streaming system over one
// camera path, measures each frame against the reference image (every needed page resident),
// runs independent configurations in parallel and writes frames.csv, summary.md/.json and plots
// (eval/evaluation_report.h).
//
// Configurations come from a JSON file (--configs) or are the product of comma-separated lists
// (eval/configurations_file.h reads and checks both).

#include <iostream>
#include <memory>

#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/output_path.h"
#include "eval/configurations_file.h"
#include "render/arithmetic_points.h"
#include "runtime/needbuffer_scale.h"
#include "workflows/evaluate_to_folder.h"

namespace vt {
namespace {

struct EvalOptions {
  FlightSceneArguments scene;
  std::string configs, output = "eval", title, referenceTexture, shard;
  ConfigurationLists lists;
  std::string hotSpot = "shifted", profile = "exact";
  uint32_t cacheFrames = 16, initialLevels = 3;
  bool preloadVisible = false, noiseSkipping = false;
  unsigned jobs = 0;
};

// The comma-separated lists whose product is the configurations flown without --configs.
void addConfigurationLists(CLI::App* command, EvalOptions& o) {
  command->add_option("--heuristic", o.lists.heuristics, "Heuristics, comma-separated")
      ->check(heuristicArgument(true))
      ->capture_default_str();
  command->add_option("--budget", o.lists.budgets, "Pages per frame, comma-separated")
      ->check(wholeNumbersIn(0, 1 << 20))
      ->capture_default_str();
  command
      ->add_option("--ancestors", o.lists.ancestors,
                   joinedNames(kAncestorStrategyNames) + "; comma-separated")
      ->capture_default_str();
  command->add_option("--locked-levels", o.lists.locked, "Locked levels, comma-separated")
      ->check(wholeNumbersIn(0, 24))
      ->capture_default_str();
  command
      ->add_option("--need-scale", o.lists.needScales,
                   "Needbuffer scales " + joinedNames(kNeedScaleNames) + "; comma-separated")
      ->capture_default_str();
  command
      ->add_option("--lookahead", o.lists.lookAheads,
                   joinedNames(kLookAheadNames) + "; comma-separated")
      ->capture_default_str();
  command
      ->add_option("--trilinear-parents", o.lists.parents,
                   "off, on: whether a needed page's parent counts as needed; comma-separated")
      ->capture_default_str();
}

// The settings every configuration shares (or, for the cache, that --configs may override).
void addSharedSettings(CLI::App* command, EvalOptions& o) {
  command->add_option("--hotspot", o.hotSpot, "HotSpot centre: " + joinedNames(kHotSpotModeNames))
      ->capture_default_str();
  command->add_flag("--noise-skipping", o.noiseSkipping, "NoiseValueSkipping (with extern)");
  command
      ->add_option("--cache-frames", o.cacheFrames,
                   "The cache holds N x N frames (with --configs: every configuration's cache)")
      ->check(wholeNumbersIn(1, 256))
      ->capture_default_str();
  command->add_option("--initial-levels", o.initialLevels, "Levels 0..K-1 loaded first")
      ->check(wholeNumbersIn(0, 24))
      ->capture_default_str();
  command->add_flag("--preload-visible", o.preloadVisible,
                    "Also load the pages the first frame needs before it (4.2.1)");
}

// How the runs are judged, run and written.
void addRunSettings(CLI::App* command, EvalOptions& o) {
  command->add_option("--profile", o.profile, "Precision profile of the oracle")
      ->check(CLI::IsMember(arithmeticPointNames()))
      ->capture_default_str();
  command->add_option("--jobs", o.jobs, "Runs at once (0: every core)")
      ->check(workerCount())
      ->capture_default_str();
  command->add_option("--title", o.title, "Title of the summary and plots");
  command
      ->add_option("--reference-texture", o.referenceTexture,
                   "Judge every frame against this texture with every needed page resident (the "
                   "same pages in another format, e.g. the uncompressed texture of a compressed "
                   "one); the summary adds the flown texture's own error against it")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--shard", o.shard,
                   "Fly only part I of N of the configurations (taken in turn) and write "
                   "shard.json for `vt merge`, which draws the plots")
      ->check(shardArgument());
  command->add_option("-o,--output", o.output, "Output folder")->capture_default_str();
}

struct FlownConfigurations {
  std::vector<FlightConfiguration> configurations;
  std::vector<EvaluationFigure> figures;
};

// The configurations file's runs, or the product of the lists.
FlownConfigurations configurationsToFly(const EvalOptions& o, const CLI::App& command) {
  FlownConfigurations flown;
  if (!o.configs.empty()) {
    // A configurations file says every setting of its runs; only the cache size, a property
    // of the regime rather than of a strategy, may be set for all of them at once (one file
    // flown on maps whose working sets differ).
    for (const char* option : {"--heuristic", "--budget", "--ancestors", "--locked-levels",
                               "--need-scale", "--lookahead", "--trilinear-parents", "--hotspot",
                               "--noise-skipping", "--initial-levels", "--preload-visible"})
      if (command.count(option) > 0)
        throw std::invalid_argument(std::string("give either --configs or ") + option);
    ConfigurationsFile loaded = loadConfigurationsFile(o.configs);
    flown.configurations = std::move(loaded.configurations);
    flown.figures = std::move(loaded.figures);
    if (command.count("--cache-frames") > 0)
      for (FlightConfiguration& c : flown.configurations) c.cacheFrames = o.cacheFrames;
  } else {
    FlightConfiguration base;
    base.hotSpot = parseHotSpotMode(o.hotSpot);
    base.noiseSkipping = o.noiseSkipping;
    base.cacheFrames = o.cacheFrames;
    base.initialLevels = o.initialLevels;
    base.preloadVisible = o.preloadVisible;
    flown.configurations = configurationProduct(o.lists, base);
  }
  return flown;
}

void runEval(const EvalOptions& o, const CLI::App& command) {
  const VirtualTextureReader reader(o.scene.texture);
  std::unique_ptr<const VirtualTextureReader> reference;
  if (!o.referenceTexture.empty())
    reference = std::make_unique<const VirtualTextureReader>(o.referenceTexture);
  const CameraPath path = o.scene.cameraPath();
  const Mesh mesh = o.scene.loadMesh();
  FlownConfigurations flown = configurationsToFly(o, command);

  // The results replace the output folder: refuse one with other files before flying.
  std::vector<std::filesystem::path> inputs = o.scene.inputs();
  inputs.push_back(o.configs);
  inputs.push_back(o.referenceTexture);
  requireOutputFolder(o.output, inputs);
  TemporaryFolder::requireReplaceable(o.output, "summary.json");
  EvaluateRequest request{
      .mesh = mesh,
      .path = path,
      .pathFile = o.scene.path,
      .configurations = std::move(flown.configurations),
      .configurationsFile = o.configs,
      .description = {.title = o.title.empty()
                                   ? std::filesystem::path(o.scene.texture).stem().string()
                                   : o.title,
                      .scene = o.scene.sceneName(),
                      .texture = o.scene.texture,
                      .jobs = 1,
                      .figures = std::move(flown.figures),
                      .referenceTexture = o.referenceTexture},
      .screen = parseSize(o.scene.size),
      .arithmetic = arithmeticPoint(o.profile),
      .jobs = o.jobs,
      .output = o.output,
      .reference = reference.get(),
      .shard = parseShardOption(o.shard)};
  evaluateToFolder(reader, std::move(request), std::cout);
}

}  // namespace

void addEvalCommand(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* command = app.add_subcommand(
      "eval", "Compare streaming configurations over a camera path against reference images");
  o->scene.addTo(command);
  command->add_option("--configs", o->configs,
                      "Configurations (.json); otherwise the product of the lists below");
  addConfigurationLists(command, *o);
  addSharedSettings(command, *o);
  addRunSettings(command, *o);
  command->callback([o, command] { runEval(*o, *command); });
}

}  // namespace vt
