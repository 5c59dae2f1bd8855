#include "render/result_set.h"

#include <algorithm>
#include <cmath>

namespace vt {
namespace {

// The page column (or row) of level `level` that a clamped coordinate in [0, 1] falls into.
int pageOf(double coordinate, int level) {
  if (!(coordinate >= 0)) return 0;
  const int last = (1 << level) - 1;
  return static_cast<int>(std::min<double>(std::floor(std::ldexp(coordinate, level)), last));
}

}  // namespace

const char* reasonName(int bit) {
  static const char* const kNames[kResultReasons] = {"coverage", "depth", "attributes", "lod",
                                                     "filter"};
  return bit >= 0 && bit < kResultReasons ? kNames[bit] : "unknown";
}

bool ambiguous(const ResultSets& sets, size_t pixel) {
  if (sets.empty()) return false;
  const uint32_t first = sets.offsets[pixel], last = sets.offsets[pixel + 1];
  if (last == first) return false;  // not built: the judged frame is identical there
  if (last - first != 1) return true;
  const Alternative& a = sets.alternatives[first];
  if (a.triangle < 0) return false;
  if (a.levelLo != a.levelHi || a.colorLo != a.colorHi) return true;
  return pageOf(a.uvLo.x, a.levelLo) != pageOf(a.uvHi.x, a.levelLo) ||
         pageOf(a.uvLo.y, a.levelLo) != pageOf(a.uvHi.y, a.levelLo);
}

}  // namespace vt
