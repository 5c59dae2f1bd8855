#include "runtime/page_priority.h"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

#include "runtime/error_gain_order.h"

namespace vt {
namespace {

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

// The value of one factor of the heuristic for one needed page.
double termOf(PriorityFactor factor, uint64_t absolute, PageId page, uint32_t residentLevel,
              const PageStatistics& statistics, const NoiseValues& noise,
              const PriorityOptions& options) {
  switch (factor) {
    case PriorityFactor::kRandom:
      return hashUnit(absolute, options.seed);
    case PriorityFactor::kPixelSum:
      return static_cast<double>(statistics.pixels);
    case PriorityFactor::kDistance:
      return 1.0 - statistics.meanDepth();
    case PriorityFactor::kWeightedPixel:
      return statistics.centreWeight;
    case PriorityFactor::kHotSpot:
      return statistics.hotSpotWeight;
    case PriorityFactor::kNoiseValue:
      return noiseToResident(page, residentLevel, noise);
    case PriorityFactor::kMipGap:
      return residentLevel == PageTable::kNone ? page.level + 1.0
                                               : static_cast<double>(page.level - residentLevel);
  }
  return 1.0;
}

// The value of each factor of the heuristic for one needed page, in the heuristic's order.
std::vector<double> termsOf(uint64_t absolute, const PageStatistics& statistics,
                            const PageTable& table, const NoiseValues& noise,
                            const PriorityOptions& options) {
  const PageId page = fromAbsoluteIndex(absolute);
  const uint32_t residentLevel = table.entry(page).z;
  std::vector<double> terms;
  for (const PriorityFactor factor : options.heuristic.factors())
    terms.push_back(termOf(factor, absolute, page, residentLevel, statistics, noise, options));
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
  const std::vector<double> values = termsOf(page, found->second, table, noise, options);
  std::vector<std::pair<std::string, double>> terms;
  for (size_t i = 0; i < values.size(); ++i)
    terms.emplace_back(nameOf(kPriorityFactorNames, options.heuristic.factors()[i]), values[i]);
  return terms;
}

AncestorStrategy parseAncestorStrategy(const std::string& name) {
  if (const auto strategy = findByName(kAncestorStrategyNames, name)) return *strategy;
  throw std::invalid_argument("ancestor strategy '" + name + "' is not one of " +
                              joinedNames(kAncestorStrategyNames));
}

std::string toString(AncestorStrategy strategy) {
  return std::string(nameOf(kAncestorStrategyNames, strategy));
}

std::vector<StreamRequest> prioritizePages(const NeedBufferAnalysis& analysis,
                                           const PageTable& table, const NoiseValues& noise,
                                           const PriorityOptions& options,
                                           const AncestorErrors& ancestorErrors) {
  // Priorities of the needed, non-resident pages, by absolute index (ordered: deterministic).
  std::map<uint64_t, double> priority;
  for (const auto& [absolute, statistics] : analysis.pages) {
    const PageId page = fromAbsoluteIndex(absolute);
    if (page.level >= table.levelCount() || table.resident(page)) continue;
    const uint32_t residentLevel = table.entry(page).z;
    double value = 1.0;
    for (const PriorityFactor factor : options.heuristic.factors())
      value *= termOf(factor, absolute, page, residentLevel, statistics, noise, options);
    priority[absolute] = value;
  }

  if (options.ancestors == AncestorStrategy::kGain)
    return orderByErrorGain(priority, table, noiseValueSums(noise));
  if (options.ancestors == AncestorStrategy::kGainSsim) {
    if (!ancestorErrors)
      throw std::invalid_argument("prioritizePages: gain_ssim without ancestor errors");
    return orderByErrorGain(priority, table, ancestorErrors);
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
