#include "render/precision_profile.h"

#include <stdexcept>

namespace vt {

PrecisionProfile parsePrecisionProfile(const std::string& name) {
  if (name == "exact") return PrecisionProfile::kExact;
  if (name == "llvmpipe") return PrecisionProfile::kLlvmpipe;
  throw std::invalid_argument("precision profile '" + name + "' is not one of exact, llvmpipe");
}

std::string toString(PrecisionProfile profile) {
  switch (profile) {
    case PrecisionProfile::kExact:
      return "exact";
    case PrecisionProfile::kLlvmpipe:
      return "llvmpipe";
  }
  return "unknown";
}

bool usesFusedPlanes(PrecisionProfile profile) { return profile == PrecisionProfile::kLlvmpipe; }
bool flushesDenormals(PrecisionProfile profile) { return profile == PrecisionProfile::kLlvmpipe; }

}  // namespace vt
