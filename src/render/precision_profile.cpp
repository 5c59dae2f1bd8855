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

// softpipe: draw_vbo sets FTZ and DAZ while it shades; only the tail of a batch with a clipped
// vertex is shaded after it returns (reference/softpipe-arithmetic.md, 5.3), which no shader value
// of this project's scenes reaches.
bool flushesDenormals(PrecisionProfile profile) { return profile != PrecisionProfile::kExact; }
bool rasterizesLikeSoftpipe(PrecisionProfile profile) {
  return profile == PrecisionProfile::kSoftpipe;
}

}  // namespace vt
