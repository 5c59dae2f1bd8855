#include "eval/flight_configuration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/resource_limits.h"
#include "runtime/needbuffer_scale.h"

namespace vt {

std::string FlightConfiguration::label() const {
  if (!name.empty()) return name;
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
  std::string text = heuristic.text();
  const auto add = [&text](const std::string& key, const std::string& value) {
    text.append(" ").append(key).append(value);
  };
  add("", budgetBytes > 0 ? std::to_string(budgetBytes) + "B/frame"
                         : std::to_string(budget) + "/frame");
  if (lookAhead != LookAhead::kNone) add("lookahead=", toString(lookAhead));
  if (lookAheadPrefetch) add("", "prefetch");
  if (lookAheadWeight > 1) add("lookahead_weight=", std::to_string(lookAheadWeight));
  if (lodBiasBacklog > 0) add("lod_bias_backlog=", std::to_string(lodBiasBacklog));
  if (heuristic.uses(PriorityFactor::kHotSpot) && hotSpot != HotSpotMode::kShifted)
    add("hotspot=", toString(hotSpot));
  if (ancestors != AncestorStrategy::kNone) add("", toString(ancestors));
  if (noiseSkipping) add("", "skipping");
  if (lockedLevels > 0) add("locked=", std::to_string(lockedLevels));
  if (needScaleLog2 > 0) add("need=1/", std::to_string(1 << needScaleLog2));
  if (asyncReadback) add("", "async");
  if (trilinearParents) add("", "parents");
  if (latency > 0) add("latency=", std::to_string(latency));
  if (cacheBytes > 0) add("cache=", std::to_string(cacheBytes) + "B");
  if (seed > 0) add("seed=", std::to_string(seed));
  if (selection != PageSelection::kHeuristic)
    add("", std::string(nameOf(kPageSelectionNames, selection)));
  return text;
}

nlohmann::json FlightConfiguration::toJson() const {
  nlohmann::json object = {{"name", label()},
          {"heuristic", heuristic.text()},
          {"ancestors", toString(ancestors)},
          {"noise_skipping", noiseSkipping},
          {"noise_threshold", noiseThreshold},
          {"lookahead", toString(lookAhead)},
          {"hotspot", toString(hotSpot)},
          {"budget", budget},
          {"latency", latency},
          {"cache_frames", cacheFrames},
          {"locked_levels", lockedLevels},
          {"initial_levels", initialLevels},
          {"preload_visible", preloadVisible},
          {"need_scale", 1 << needScaleLog2},
          {"readback", std::string(nameOf(kReadbackNames, asyncReadback))},
          {"trilinear_parents", trilinearParents},
          {"seed", seed}};
  // Only where set: every configuration written before byte budgets reads the same.
  if (budgetBytes > 0) object["budget_bytes"] = budgetBytes;
  if (lookAheadPrefetch) object["lookahead_pages"] = "prefetch";
  if (lookAheadWeight > 1) object["lookahead_weight"] = lookAheadWeight;
  if (lodBiasBacklog > 0) object["lod_bias_backlog"] = lodBiasBacklog;
  if (cacheBytes > 0) object["cache_bytes"] = cacheBytes;
  if (selection != PageSelection::kHeuristic) {
    object["selection"] = std::string(nameOf(kPageSelectionNames, selection));
    object["ceiling_candidates"] = ceilingCandidates;
  }
  return object;
}

namespace {

// "lookahead_pages": whether the LookAhead camera's pages are prefetched (else merged).
bool prefetchesLookAhead(const std::string& value) {
  const auto pages = findByName(kLookAheadPagesNames, value);
  if (!pages)
    throw std::invalid_argument("'lookahead_pages' must be " +
                                joinedNames(kLookAheadPagesNames, " or "));
  return *pages;
}

// Keys that each read well but do not go together.
void refuseConflicts(const FlightConfiguration& c) {
  if (c.selection != PageSelection::kHeuristic && (c.budgetBytes > 0 || c.latency > 0))
    throw std::invalid_argument(
        "'selection' ceiling picks pages for the next frame: it needs a budget in pages "
        "('budget') and no 'budget_bytes' or 'latency'");
  if (c.lookAheadWeight > 1 && (c.lookAhead == LookAhead::kNone || c.lookAheadPrefetch))
    throw std::invalid_argument(
        "'lookahead_weight' weights the LookAhead camera's merged pixels: it needs a "
        "'lookahead' other than none and 'lookahead_pages' merged");
  if (c.lookAheadPrefetch && c.lookAhead == LookAhead::kNone)
    throw std::invalid_argument(
        "'lookahead_pages' prefetch prefetches the LookAhead camera's pages: it needs a "
        "'lookahead' other than none");
}

}  // namespace

FlightConfiguration FlightConfiguration::fromJson(const nlohmann::json& object,
                                                  const FlightConfiguration& defaults) {
  if (!object.is_object()) throw std::invalid_argument("a configuration must be a JSON object");
  FlightConfiguration c = defaults;
  for (const auto& item : object.items()) {
    // Named, not structured bindings: the lambdas below capture them, which clang before 16
    // (the fuzz build's) refuses for bindings.
    const std::string& key = item.key();
    const nlohmann::json& value = item.value();
    const auto text = [&] {
      if (!value.is_string()) throw std::invalid_argument("'" + key + "' must be a string");
      return value.get<std::string>();
    };
    const auto flag = [&] {
      if (!value.is_boolean()) throw std::invalid_argument("'" + key + "' must be true or false");
      return value.get<bool>();
    };
    const auto bytes = [&] {
      if (!value.is_number_integer() || value.get<int64_t>() < 0 ||
          value.get<int64_t>() > (int64_t{1} << 40))
        throw std::invalid_argument("'" + key + "' must be a whole number from 0 to 2^40");
      return static_cast<uint64_t>(value.get<int64_t>());
    };
    const auto count = [&](uint32_t low, uint32_t high) {
      if (!value.is_number_integer() || value.get<int64_t>() < low || value.get<int64_t>() > high)
        throw std::invalid_argument("'" + key + "' must be a whole number from " +
                                    std::to_string(low) + " to " + std::to_string(high));
      return static_cast<uint32_t>(value.get<int64_t>());
    };
    if (key == "name") {
      c.name = text();
    } else if (key == "heuristic") {
      c.heuristic = Heuristic::parse(text());
    } else if (key == "ancestors") {
      c.ancestors = parseAncestorStrategy(text());
    } else if (key == "noise_skipping") {
      c.noiseSkipping = flag();
    } else if (key == "noise_threshold") {
      // Finite as the float it is kept in: 1e300 would become infinity, which the written
      // configuration (summary.json) could not hold.
      if (!value.is_number() || !std::isfinite(value.get<double>()) ||
          std::abs(value.get<double>()) > std::numeric_limits<float>::max())
        throw std::invalid_argument("'noise_threshold' must be a finite number (a float)");
      c.noiseThreshold = value.get<float>();
    } else if (key == "lookahead") {
      c.lookAhead = parseLookAhead(text());
    } else if (key == "lookahead_pages") {
      c.lookAheadPrefetch = prefetchesLookAhead(text());
    } else if (key == "lookahead_weight") {
      c.lookAheadWeight = count(1, 16);
    } else if (key == "lod_bias_backlog") {
      c.lodBiasBacklog = count(0, 1u << 20);
    } else if (key == "hotspot") {
      c.hotSpot = parseHotSpotMode(text());
    } else if (key == "budget") {
      c.budget = count(0, 1u << 20);
    } else if (key == "budget_bytes") {
      c.budgetBytes = bytes();
    } else if (key == "latency") {
      c.latency = count(0, 1000);
    } else if (key == "cache_bytes") {
      c.cacheBytes = bytes();
    } else if (key == "cache_frames") {
      c.cacheFrames = count(1, 256);
    } else if (key == "locked_levels") {
      c.lockedLevels = count(0, 24);
    } else if (key == "initial_levels") {
      c.initialLevels = count(0, 24);
    } else if (key == "preload_visible") {
      c.preloadVisible = flag();
    } else if (key == "need_scale") {
      if (!value.is_number_integer())
        throw std::invalid_argument("'need_scale' must be 1, 2, 4 or 8");
      c.needScaleLog2 = parseNeedScale(std::to_string(value.get<int64_t>()));
    } else if (key == "trilinear_parents") {
      c.trilinearParents = flag();
    } else if (key == "seed") {
      c.seed = count(0, 1u << 30);
    } else if (key == "readback") {
      const auto mode = findByName(kReadbackNames, text());
      if (!mode)
        throw std::invalid_argument("'readback' must be " + joinedNames(kReadbackNames, " or "));
      c.asyncReadback = *mode;
    } else if (key == "selection") {
      const auto selection = findByName(kPageSelectionNames, text());
      if (!selection)
        throw std::invalid_argument("'selection' must be " +
                                    joinedNames(kPageSelectionNames, " or "));
      c.selection = *selection;
    } else if (key == "ceiling_candidates") {
      c.ceilingCandidates = count(1, 1024);
    } else {
      throw std::invalid_argument("unknown configuration key '" + key + "'");
    }
  }
  refuseConflicts(c);
  return c;
}

uint32_t cacheFramesFor(const FlightConfiguration& c, const TextureDescription& d) {
  if (c.cacheBytes == 0) return std::max(1u, c.cacheFrames);
  const uint64_t frames = c.cacheBytes / d.storedPageBytes();
  auto side = static_cast<uint64_t>(std::sqrt(static_cast<double>(frames)));
  while (side * side > frames) --side;  // the square root's rounding, either way
  while ((side + 1) * (side + 1) <= frames) ++side;
  // No larger than cache_frames allows, nor than one cache texture holds (resource_limits.h).
  const uint64_t largest =
      std::clamp<uint64_t>(kMaxCacheSideTexels / d.storedPageSide(), 1, 256);
  return static_cast<uint32_t>(std::clamp<uint64_t>(side, 1, largest));
}

}  // namespace vt
