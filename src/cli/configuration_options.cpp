#include "cli/configuration_options.h"

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "cli/argument_checks.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/json_text.h"
#include "eval/configurations_file.h"
#include "runtime/needbuffer_scale.h"
#include "scene/box_room.h"
#include "scene/obj_mesh.h"

namespace vt {

void FlightSceneArguments::addTo(CLI::App* command) {
  command->add_option("TEXTURE", texture, "Virtual-texture file (.vt)")->required();
  command->add_option("--path", path,
                      "Camera path or storyboard (.json); default: a turn around the box room");
  command->add_option("--mesh", mesh,
                      "OBJ mesh with virtual texture coordinates (default: the box room)");
  command->add_option("--size", size, "WIDTHxHEIGHT")
      ->check(sizeValidator())
      ->capture_default_str();
}

CameraPath FlightSceneArguments::cameraPath() const {
  return path.empty() ? boxRoomPath() : CameraPath::load(path);
}

Mesh FlightSceneArguments::loadMesh() const { return mesh.empty() ? boxRoom() : loadObjMesh(mesh); }

std::string FlightSceneArguments::sceneName() const { return mesh.empty() ? "box room" : mesh; }

struct ConfigurationOptions::Values {
  std::string config, configName, heuristic = "pixelsum", ancestors = "none", lookAhead = "none",
                                    lookAheadPages = "merged", hotSpot = "shifted",
                                    needScale = "1", readback = "sync";
  uint32_t budget = 10, latency = 0, lockedLevels = 0, initialLevels = 3, frames = 16;
  uint32_t lookAheadWeight = 1, lodBiasBacklog = 0;
  uint64_t budgetBytes = 0, cacheBytes = 0;
  float noiseThreshold = -1.0f;
  bool noiseSkipping = false, preloadVisible = false, trilinearParents = false;
};

ConfigurationOptions::ConfigurationOptions(CLI::App* command)
    : values_(std::make_shared<Values>()), command_(command) {
  Values& v = *values_;
  CLI::Option* config =
      command->add_option("--config", v.config,
                          "Configuration (.json, the keys of the options below); options given "
                          "as well override it");
  command
      ->add_option("--config-name", v.configName,
                   "With --config naming a configurations file (vt eval's --configs, e.g. "
                   "data/chapter4/beyond.json): its configuration of this name")
      ->needs(config);
  command->add_option("--budget", v.budget, "Pages streamed per frame (thesis 4.1.1)")
      ->check(wholeNumbersIn(0, 1 << 20))
      ->capture_default_str();
  command
      ->add_option("--budget-bytes", v.budgetBytes,
                   "Bytes streamed per frame instead of pages, at the pages' stored size "
                   "(compressed pages are smaller); 0: the page budget")
      ->check(CLI::Range(uint64_t{0}, uint64_t{1} << 40))
      ->capture_default_str();
  command->add_option("--latency", v.latency, "Frames between a request and its page's arrival")
      ->check(wholeNumbersIn(0, 1000))
      ->capture_default_str();
  command
      ->add_option("--need-scale", v.needScale,
                   "Needbuffer at 1/N of the resolution per axis, jittered per frame: " +
                       joinedNames(kNeedScaleNames))
      ->check(CLI::IsMember(namesOf(kNeedScaleNames)))
      ->capture_default_str();
  command
      ->add_option("--heuristic", v.heuristic,
                   "Factors joined by '*': " + joinedNames(kPriorityFactorNames))
      ->check(heuristicArgument())
      ->capture_default_str();
  command
      ->add_option("--ancestors", v.ancestors,
                   "Ancestor streaming: " + joinedNames(kAncestorStrategyNames))
      ->check(CLI::IsMember(namesOf(kAncestorStrategyNames)))
      ->capture_default_str();
  command->add_flag("--noise-skipping", v.noiseSkipping, "NoiseValueSkipping (with extern)");
  command
      ->add_option("--lookahead", v.lookAhead,
                   "LookAhead camera (4.2.4): " + joinedNames(kLookAheadNames))
      ->check(CLI::IsMember(namesOf(kLookAheadNames)))
      ->capture_default_str();
  addBeyondTheThesisOptions();
  command
      ->add_option("--hotspot", v.hotSpot,
                   "HotSpot centre (4.2.3.1): " + joinedNames(kHotSpotModeNames))
      ->check(CLI::IsMember(namesOf(kHotSpotModeNames)))
      ->capture_default_str();
  command
      ->add_option("--noise-threshold", v.noiseThreshold,
                   "NoiseValueSkipping threshold (default: the mean NoiseValue)")
      ->check(finiteNumber());
  command
      ->add_option("--locked-levels", v.lockedLevels, "Levels 0..K-1 never leave the cache (4.3.1)")
      ->check(wholeNumbersIn(0, 24))
      ->capture_default_str();
  command
      ->add_option("--initial-levels", v.initialLevels,
                   "Levels 0..K-1 loaded before the first frame (4.2.1)")
      ->check(wholeNumbersIn(0, 24))
      ->capture_default_str();
  command->add_flag("--preload-visible", v.preloadVisible,
                    "Also load the pages the first frame needs before it (4.2.1)");
  command->add_flag("--trilinear-parents", v.trilinearParents,
                    "A needed page's parent, which trilinear filtering reads, counts as needed");
  command->add_option("--cache-frames", v.frames, "The cache holds N x N frames")
      ->check(wholeNumbersIn(1, 256))
      ->capture_default_str();
  command
      ->add_option("--cache-bytes", v.cacheBytes,
                   "The cache holds as many N x N frames as fit in these bytes at the pages' "
                   "stored size (compressed pages fit more) instead of --cache-frames; 0: "
                   "--cache-frames")
      ->check(CLI::Range(uint64_t{0}, uint64_t{1} << 40))
      ->capture_default_str();
  command
      ->add_option("--readback", v.readback,
                   "sync, or async: the analysis sees the previous frame's needbuffer (GL: "
                   "pixel-buffer objects and a fence)")
      ->check(CLI::IsMember(namesOf(kReadbackNames)))
      ->capture_default_str();
}

void ConfigurationOptions::addBeyondTheThesisOptions() {
  CLI::App* command = command_;
  Values& v = *values_;
  command
      ->add_option("--lookahead-pages", v.lookAheadPages,
                   "The LookAhead camera's pages merged with the frame's (4.2.4), or prefetched "
                   "into the slots the frame's own requests leave")
      ->check(CLI::IsMember(namesOf(kLookAheadPagesNames)))
      ->capture_default_str();
  command
      ->add_option("--lookahead-weight", v.lookAheadWeight,
                   "Each merged LookAhead pixel counts this many times against a drawn one")
      ->check(wholeNumbersIn(1, 16))
      ->capture_default_str();
  command
      ->add_option("--lod-bias-backlog", v.lodBiasBacklog,
                   "When more needed pages than this are missing, request each missing page's "
                   "parent first (0: never)")
      ->check(wholeNumbersIn(0, 1 << 20))
      ->capture_default_str();
}

std::filesystem::path ConfigurationOptions::file() const { return values_->config; }

FlightConfiguration ConfigurationOptions::configuration() const {
  const Values& v = *values_;
  FlightConfiguration base;
  if (!v.configName.empty()) {
    base = loadNamedConfiguration(v.config, v.configName);
  } else if (!v.config.empty()) {
    try {
      base = FlightConfiguration::fromJson(readJsonFile(v.config, "configuration"), base);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(v.config, "not a configuration: " + jsonErrorText(e));
    } catch (const std::invalid_argument& e) {
      throw InputError(v.config, e.what());
    }
  }
  // Options on the command line (or all of them, without --config) as JSON keys.
  const bool all = v.config.empty();
  const auto given = [&](const char* option) { return all || command_->count(option) > 0; };
  nlohmann::json options = nlohmann::json::object();
  if (given("--heuristic")) options["heuristic"] = v.heuristic;
  if (given("--ancestors")) options["ancestors"] = v.ancestors;
  if (given("--noise-skipping")) options["noise_skipping"] = v.noiseSkipping;
  if (given("--noise-threshold")) options["noise_threshold"] = v.noiseThreshold;
  if (given("--lookahead")) options["lookahead"] = v.lookAhead;
  if (given("--lookahead-pages")) options["lookahead_pages"] = v.lookAheadPages;
  if (given("--lookahead-weight")) options["lookahead_weight"] = v.lookAheadWeight;
  if (given("--lod-bias-backlog")) options["lod_bias_backlog"] = v.lodBiasBacklog;
  if (given("--hotspot")) options["hotspot"] = v.hotSpot;
  if (given("--budget")) options["budget"] = v.budget;
  // Only where given or set: a configuration without it reads as before byte budgets.
  if (command_->count("--budget-bytes") > 0 || (all && v.budgetBytes > 0))
    options["budget_bytes"] = v.budgetBytes;
  if (given("--latency")) options["latency"] = v.latency;
  if (given("--cache-frames")) options["cache_frames"] = v.frames;
  if (command_->count("--cache-bytes") > 0 || (all && v.cacheBytes > 0))
    options["cache_bytes"] = v.cacheBytes;
  if (given("--locked-levels")) options["locked_levels"] = v.lockedLevels;
  if (given("--initial-levels")) options["initial_levels"] = v.initialLevels;
  if (given("--preload-visible")) options["preload_visible"] = v.preloadVisible;
  if (given("--need-scale")) options["need_scale"] = std::stoi(v.needScale);
  if (given("--readback")) options["readback"] = v.readback;
  if (given("--trilinear-parents")) options["trilinear_parents"] = v.trilinearParents;
  return FlightConfiguration::fromJson(options, base);
}

}  // namespace vt
