#include "runtime/needbuffer_scale.h"

#include <algorithm>
#include <stdexcept>

namespace vt {
namespace {

// The radical inverse of n in `base`: the Halton sequence's n-th value in [0, 1).
float radicalInverse(uint64_t n, uint32_t base) {
  double value = 0.0, scale = 1.0 / base;
  for (; n > 0; n /= base, scale /= base) value += static_cast<double>(n % base) * scale;
  return static_cast<float>(value);
}

}  // namespace

Viewport reducedViewport(Viewport screen, int scaleLog2) {
  return {std::max(1, screen.width >> scaleLog2), std::max(1, screen.height >> scaleLog2)};
}

glm::vec2 needJitter(uint64_t frame, int scaleLog2) {
  if (scaleLog2 == 0) return glm::vec2(0.0f);
  // Index from 1: the sequence's 0th point is the corner (0, 0).
  return glm::vec2(radicalInverse(frame + 1, 2), radicalInverse(frame + 1, 3)) - 0.5f;
}

int parseNeedScale(const std::string& text) {
  if (const auto scaleLog2 = findByName(kNeedScaleNames, text)) return *scaleLog2;
  throw std::invalid_argument("needbuffer scale '" + text + "' is not " +
                              joinedNames(kNeedScaleNames, " or "));
}

}  // namespace vt
