#include "runtime/heuristic.h"

#include <algorithm>
#include <stdexcept>

namespace vt {

Heuristic Heuristic::parse(std::string_view text) {
  // Split at '*' as std::getline does: a trailing '*' ends the last factor, it adds no empty one.
  std::vector<std::string_view> names;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('*', start), text.size());
    names.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  if (names.empty()) throw std::invalid_argument("heuristic: empty");
  Heuristic heuristic;
  heuristic.factors_.clear();
  for (const std::string_view name : names) {
    const auto factor = findByName(kPriorityFactorNames, name);
    if (!factor)
      throw std::invalid_argument("heuristic: '" + std::string(name) + "' is not one of " +
                                  joinedNames(kPriorityFactorNames));
    heuristic.factors_.push_back(*factor);
  }
  return heuristic;
}

bool Heuristic::uses(PriorityFactor factor) const {
  return std::find(factors_.begin(), factors_.end(), factor) != factors_.end();
}

std::string Heuristic::text() const {
  std::string text;
  for (const PriorityFactor factor : factors_)
    text.append(text.empty() ? "" : "*").append(nameOf(kPriorityFactorNames, factor));
  return text;
}

}  // namespace vt
