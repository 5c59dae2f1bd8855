#include "render/precision_profile.h"

#include <stdexcept>

namespace vt {

PrecisionProfile parsePrecisionProfile(const std::string& name) {
  if (const auto profile = findByName(kPrecisionProfileNames, name)) return *profile;
  throw std::invalid_argument("precision profile '" + name + "' is not one of " +
                              joinedNames(kPrecisionProfileNames));
}

std::string toString(PrecisionProfile profile) {
  return std::string(nameOf(kPrecisionProfileNames, profile));
}

}  // namespace vt
