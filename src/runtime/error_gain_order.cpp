#include "runtime/error_gain_order.h"

#include <algorithm>
#include <queue>
#include <unordered_map>

namespace vt {
namespace {

// A needed page: its weight, the level it is now served from, and its error through each level
// from its resident one down: error[l - resident] = E_q(l).
struct Needed {
  double weight = 0.0;
  int served = 0;
  int resident = 0;
  std::vector<double> error;
  double errorAt(int level) const { return error[static_cast<size_t>(level - resident)]; }
};

// A page that may be streamed: the needed pages of its subtree it would serve better.
struct Candidate {
  uint64_t page = 0;
  int level = 0;
  std::vector<size_t> below;
  double subtreeWeight = 0.0;
};

double gainOf(const Candidate& c, const std::vector<Needed>& needed) {
  double gain = 0.0;
  for (const size_t q : c.below) {
    const Needed& n = needed[q];
    if (n.served < c.level) gain += n.weight * (n.errorAt(n.served) - n.errorAt(c.level));
  }
  return gain;
}

// The heap's entry: a candidate's gain when last priced; the best on top.
struct Priced {
  double gain = 0.0, subtreeWeight = 0.0;
  uint64_t page = 0;
  size_t candidate = 0;
  bool operator<(const Priced& o) const {
    if (gain != o.gain) return gain < o.gain;
    if (subtreeWeight != o.subtreeWeight) return subtreeWeight < o.subtreeWeight;
    return page > o.page;
  }
};

}  // namespace

AncestorErrors noiseValueSums(const NoiseValues& noise) {
  // One walk up from the page: E_q(l) is the running sum once level l + 1 is added.
  return [noise](PageId page) {
    std::vector<double> row(page.level, 0.0);
    double sum = 0.0;
    for (PageId p = page; p.level > 0; p = parent(p)) {
      sum += static_cast<double>(noise(p));
      row[p.level - 1] = sum;
    }
    return row;
  };
}

std::vector<StreamRequest> orderByErrorGain(const std::map<uint64_t, double>& weight,
                                            const PageTable& table, const AncestorErrors& error) {
  std::vector<Needed> needed;
  std::vector<Candidate> candidates;
  std::unordered_map<uint64_t, size_t> candidateOf;
  for (const auto& [absolute, w] : weight) {
    const PageId page = fromAbsoluteIndex(absolute);
    const uint32_t entry = table.entry(page).z;
    const int resident = entry == PageTable::kNone ? -1 : static_cast<int>(entry);
    Needed n;
    n.weight = w;
    n.served = n.resident = resident;
    n.error.assign(static_cast<size_t>(static_cast<int>(page.level) - resident + 1), 0.0);
    const std::vector<double> row = error(page);
    for (int level = static_cast<int>(page.level); level > resident; --level) {
      const PageId at = ancestorAt(page, static_cast<uint32_t>(level));
      // Nothing resident (level 0's entry): shown as nothing, no better than through the root.
      const double through = level > 0 ? row[static_cast<size_t>(level - 1)] : 0.0;
      n.error[static_cast<size_t>(level - 1 - resident)] = std::max(n.errorAt(level), through);
      const uint64_t index = absoluteIndex(at);
      auto [found, added] = candidateOf.try_emplace(index, candidates.size());
      if (added) candidates.push_back({index, level, {}, 0.0});
      candidates[found->second].below.push_back(needed.size());
      candidates[found->second].subtreeWeight += w;
    }
    needed.push_back(std::move(n));
  }

  std::priority_queue<Priced> heap;
  for (size_t c = 0; c < candidates.size(); ++c)
    heap.push({gainOf(candidates[c], needed), candidates[c].subtreeWeight, candidates[c].page, c});
  std::vector<StreamRequest> order;
  order.reserve(candidates.size());
  while (!heap.empty()) {
    Priced top = heap.top();
    heap.pop();
    const Candidate& c = candidates[top.candidate];
    const double gain = gainOf(c, needed);
    if (gain < top.gain) {  // priced again: back in line, taken when it leads at its price
      top.gain = gain;
      heap.push(top);
      continue;
    }
    order.push_back({c.page, gain});
    for (const size_t q : c.below) needed[q].served = std::max(needed[q].served, c.level);
  }
  return order;
}

}  // namespace vt
