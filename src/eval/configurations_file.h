#pragma once
// The configurations `vt eval` compares (thesis chapter 4), read and checked before the first
// frame is flown: from a configurations file, or as the product of lists of settings.
//
// A configurations file is a list of configurations in eval/flight_configuration.h's form, or
//   { "defaults": {...}, "configurations": [{...}, ...],
//     "figures": [{ "file": "basic.png", "title": "...", "measure": "ssim", "runs": ["name", ...]
//     }] }
// where the defaults fill the keys a configuration leaves out, the configurations' labels must
// differ, and a figure names runs by label, its file a plain name.png, its measure ssim, wssim or
// rmse.

#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "eval/evaluation_report.h"
#include "eval/flight_configuration.h"

namespace vt {

struct ConfigurationsFile {
  std::vector<FlightConfiguration> configurations;
  std::vector<EvaluationFigure> figures;
};

// Throws std::invalid_argument naming the configuration (from 1) or figure and what is wrong, or
// nlohmann::json::exception for a value of the wrong type.
ConfigurationsFile parseConfigurationsFile(const nlohmann::json& root);

// Throws InputError naming `file` and what is wrong.
ConfigurationsFile loadConfigurationsFile(const std::filesystem::path& file);

// The configuration named `name` in the configurations file `file`, as `vt eval` would fly it
// (its defaults applied). Throws InputError naming `file` and what is wrong, or the names it
// holds when none is `name`.
FlightConfiguration loadNamedConfiguration(const std::filesystem::path& file,
                                           const std::string& name);

// Comma-separated lists of settings, as `vt eval --heuristic pixelsum,random --budget 5,10` gives
// them; empty items are skipped, an empty list is an error.
struct ConfigurationLists {
  std::string heuristics = "pixelsum", budgets = "5,10", ancestors = "none", locked = "0",
              needScales = "1", lookAheads = "none", parents = "off";
};

// Every combination of the lists over `base`: heuristic x budget x ancestors x locked levels x
// needbuffer scale x lookahead x trilinear parents, the last varying fastest. Throws
// std::invalid_argument naming the bad item.
std::vector<FlightConfiguration> configurationProduct(const ConfigurationLists& lists,
                                                      const FlightConfiguration& base);

}  // namespace vt
