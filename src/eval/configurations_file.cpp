#include "eval/configurations_file.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/error.h"
#include "common/json_text.h"

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

}  // namespace

ConfigurationsFile parseConfigurationsFile(const nlohmann::json& root) {
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
}

ConfigurationsFile loadConfigurationsFile(const std::filesystem::path& file) {
  try {
    return parseConfigurationsFile(readJsonFile(file, "configurations"));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "not a configurations file: " + jsonErrorText(e));
  } catch (const std::invalid_argument& e) {
    throw InputError(file, e.what());
  }
}

FlightConfiguration loadNamedConfiguration(const std::filesystem::path& file,
                                           const std::string& name) {
  const ConfigurationsFile loaded = loadConfigurationsFile(file);
  std::string names;
  for (const FlightConfiguration& c : loaded.configurations) {
    if (c.label() == name) return c;
    names += (names.empty() ? "'" : ", '") + c.label() + "'";
  }
  throw InputError(file, "no configuration named '" + name + "' (it holds " + names + ")");
}

std::vector<FlightConfiguration> configurationProduct(const ConfigurationLists& lists,
                                                      const FlightConfiguration& base) {
  std::vector<FlightConfiguration> configurations;
  for (const std::string& heuristic : splitList(lists.heuristics))
    for (const std::string& budget : splitList(lists.budgets))
      for (const std::string& ancestors : splitList(lists.ancestors))
        for (const std::string& locked : splitList(lists.locked))
          for (const std::string& scale : splitList(lists.needScales))
            for (const std::string& lookAhead : splitList(lists.lookAheads))
              for (const std::string& parents : splitList(lists.parents)) {
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
                  throw std::invalid_argument("not a whole number in '" + budget + "', '" + locked +
                                              "' or '" + scale + "'");
                }
                configurations.push_back(FlightConfiguration::fromJson(settings, base));
              }
  return configurations;
}

}  // namespace vt
