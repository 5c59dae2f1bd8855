#include "runtime/page_priority.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace vt {
namespace {

const std::set<std::string> kFactors = {"random",  "pixelsum",   "distance", "weightedpixel",
                                        "hotspot", "noisevalue", "mipgap"};

std::vector<std::string> factorsOf(const std::string& heuristic) {
  std::vector<std::string> factors;
  std::stringstream stream(heuristic);
  for (std::string factor; std::getline(stream, factor, '*');) factors.push_back(factor);
  return factors;
}

// A uniform value in [0, 1) from the page and the seed (splitmix64).
double hashUnit(uint64_t page, uint64_t seed) {
  uint64_t z = page * 0x9e3779b97f4a7c15ull + seed * 0xbf58476d1ce4e5b9ull + 0x94d049bb133111ebull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

// Sum of NoiseValues from `page` up to, not including, its resident ancestor on `residentLevel`
// (all the way to the root when nothing is resident): each measures a page against its parent.
double noiseToResident(PageId page, uint32_t residentLevel, const NoiseValues& noise) {
  const bool none = residentLevel == PageTable::kNone;
  double sum = 0.0;
  for (PageId p = page;; p = parent(p)) {
    if (!none && p.level <= residentLevel) break;
    sum += noise(p);
    if (p.level == 0) break;
  }
  return sum;
}

// The value of each factor of the heuristic for one needed page, in the heuristic's order.
std::vector<std::pair<std::string, double>> termsOf(
    const std::vector<std::string>& factors, uint64_t absolute, const PageStatistics& statistics,
    const PageTable& table, const NoiseValues& noise, const PriorityOptions& options) {
  const PageId page = fromAbsoluteIndex(absolute);
  const uint32_t residentLevel = table.entry(page).z;
  std::vector<std::pair<std::string, double>> terms;
  for (const std::string& factor : factors) {
    double value = 1.0;
    if (factor == "random")
      value = hashUnit(absolute, options.seed);
    else if (factor == "pixelsum")
      value = static_cast<double>(statistics.pixels);
    else if (factor == "distance")
      value = 1.0 - statistics.meanDepth();
    else if (factor == "weightedpixel")
      value = statistics.centreWeight;
    else if (factor == "hotspot")
      value = statistics.hotSpotWeight;
    else if (factor == "noisevalue")
      value = noiseToResident(page, residentLevel, noise);
    else if (factor == "mipgap")
      value = residentLevel == PageTable::kNone ? page.level + 1.0
                                                : static_cast<double>(page.level - residentLevel);
    terms.emplace_back(factor, value);
  }
  return terms;
}

}  // namespace

std::vector<std::pair<std::string, double>> priorityTerms(uint64_t page,
                                                          const NeedBufferAnalysis& analysis,
                                                          const PageTable& table,
                                                          const NoiseValues& noise,
                                                          const PriorityOptions& options) {
  const auto found = analysis.pages.find(page);
  if (found == analysis.pages.end()) return {};
  return termsOf(factorsOf(options.heuristic), page, found->second, table, noise, options);
}

void validateHeuristic(const std::string& heuristic) {
  const auto factors = factorsOf(heuristic);
  if (factors.empty()) throw std::invalid_argument("heuristic: empty");
  for (const std::string& factor : factors)
    if (!kFactors.count(factor))
      throw std::invalid_argument(
          "heuristic: '" + factor +
          "' is not one of random, pixelsum, distance, weightedpixel, hotspot, "
          "noisevalue, mipgap");
}

AncestorStrategy parseAncestorStrategy(const std::string& name) {
  if (name == "none") return AncestorStrategy::kNone;
  if (name == "intern") return AncestorStrategy::kIntern;
  if (name == "extern") return AncestorStrategy::kExtern;
  throw std::invalid_argument("ancestor strategy '" + name +
                              "' is not one of none, intern, extern");
}

std::vector<StreamRequest> prioritizePages(const NeedBufferAnalysis& analysis,
                                           const PageTable& table, const NoiseValues& noise,
                                           const PriorityOptions& options) {
  validateHeuristic(options.heuristic);
  const std::vector<std::string> factors = factorsOf(options.heuristic);

  // Priorities of the needed, non-resident pages, by absolute index (ordered: deterministic).
  std::map<uint64_t, double> priority;
  for (const auto& [absolute, statistics] : analysis.pages) {
    const PageId page = fromAbsoluteIndex(absolute);
    if (page.level >= table.levelCount() || table.resident(page)) continue;
    double value = 1.0;
    for (const auto& [factor, term] : termsOf(factors, absolute, statistics, table, noise, options))
      value *= term;
    priority[absolute] = value;
  }

  if (options.ancestors != AncestorStrategy::kNone) {
    // Ancestors get the sum of their children's priorities: finest levels first, so that each
    // page's priority is complete before it passes it on.
    for (uint32_t level = table.levelCount(); level-- > 1;) {
      const auto first = priority.lower_bound(firstPageOfLevel(level));
      const auto last = priority.lower_bound(firstPageOfLevel(level + 1));
      std::vector<std::pair<uint64_t, double>> pages(first, last);
      for (const auto& [absolute, value] : pages) {
        const PageId page = fromAbsoluteIndex(absolute);
        const PageId up = parent(page);
        if (table.resident(up)) continue;
        if (options.noiseValueSkipping && noise(page) < options.noiseThreshold) continue;
        priority[absoluteIndex(up)] += value;
      }
    }
  }

  std::vector<StreamRequest> requests;
  requests.reserve(priority.size());
  for (const auto& [page, value] : priority) requests.push_back({page, value});
  const auto byPriority = [](const StreamRequest& a, const StreamRequest& b) {
    return a.priority != b.priority ? a.priority > b.priority : a.page < b.page;
  };
  if (options.ancestors == AncestorStrategy::kExtern) {
    std::sort(requests.begin(), requests.end(),
              [&](const StreamRequest& a, const StreamRequest& b) {
                const uint32_t la = levelOfAbsoluteIndex(a.page), lb = levelOfAbsoluteIndex(b.page);
                return la != lb ? la < lb : byPriority(a, b);
              });
    return requests;
  }
  std::sort(requests.begin(), requests.end(), byPriority);
  if (options.ancestors == AncestorStrategy::kIntern) {
    // In priority order, but every page's requested ancestors first, coarsest first.
    std::vector<StreamRequest> ordered;
    std::set<uint64_t> emitted;
    for (const StreamRequest& request : requests) {
      std::vector<uint64_t> chain;
      for (PageId p = fromAbsoluteIndex(request.page);; p = parent(p)) {
        const uint64_t absolute = absoluteIndex(p);
        if (priority.count(absolute) && !emitted.count(absolute)) chain.push_back(absolute);
        if (p.level == 0) break;
      }
      for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        emitted.insert(*it);
        ordered.push_back({*it, priority[*it]});
      }
    }
    return ordered;
  }
  return requests;
}

}  // namespace vt
