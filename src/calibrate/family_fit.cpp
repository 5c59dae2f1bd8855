#include "calibrate/family_fit.h"

#include <stdexcept>

namespace vt::calibrate {

size_t ParameterFit::choose() {
  size_t best = 0;
  for (size_t i = 0; i < members.size(); ++i)
    if (members[i].mismatches < members[best].mismatches) best = i;
  if (members.empty()) return 0;
  chosen = members[best].member;
  consistent.clear();
  for (const MemberResult& m : members)
    if (m.mismatches == 0) consistent.push_back(m.member);
  mismatches = members[best].mismatches;
  pinned = mismatches == 0;
  return best;
}

std::string ParameterFit::memberSummary() const {
  std::string text;
  for (const MemberResult& m : members)
    text += (text.empty() ? "" : ", ") + m.member + " " + differ(m.mismatches, probes);
  return text;
}

const ParameterFit& fitNamed(const std::vector<ParameterFit>& fits, const std::string& parameter) {
  for (const ParameterFit& fit : fits)
    if (fit.parameter == parameter) return fit;
  throw std::logic_error("calibration: no fit of " + parameter);
}

std::string differ(uint64_t mismatches, uint64_t probes) {
  return std::to_string(mismatches) + " of " + std::to_string(probes) + " differ";
}

}  // namespace vt::calibrate
