#include "render/result_set.h"

#include <algorithm>
#include <cmath>

#include "format/page_address.h"

namespace vt {

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
  return pageAt(a.uvLo.x, a.levelLo) != pageAt(a.uvHi.x, a.levelLo) ||
         pageAt(a.uvLo.y, a.levelLo) != pageAt(a.uvHi.y, a.levelLo);
}

}  // namespace vt
