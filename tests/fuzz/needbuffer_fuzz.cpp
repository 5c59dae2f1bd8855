// Fuzz target: needbuffer readbacks decoded on the CPU (shader/needbuffer.h) and analysed
// (runtime/needbuffer_analysis.h).

#include <bit>
#include <cstring>
#include <vector>

#include "fuzz/fuzz_targets.h"
#include "runtime/needbuffer_analysis.h"
#include "shader/needbuffer.h"

namespace vt::fuzz {

// Byte 0: bit 0 the 8-bit encoding, bit 1 depth, bit 2 centre weights, bit 3 a hot spot.
// Bytes 1-2: the width minus one (little-endian). Then 16 bytes per pixel, RGBA32UI, as many
// whole rows as the input holds; each pixel's depth is its red channel's bits as a float.
void needBuffer(Input input) {
  if (input.size() < 3) return;
  const uint8_t flags = input[0];
  const int width = 1 + (input[1] | (input[2] << 8));
  const size_t values = (input.size() - 3) / sizeof(glm::uvec4);
  const int height = static_cast<int>(values / static_cast<size_t>(width));
  std::vector<glm::uvec4> need(static_cast<size_t>(width) * static_cast<size_t>(height));
  if (!need.empty()) std::memcpy(need.data(), input.data() + 3, need.size() * sizeof(glm::uvec4));
  std::vector<float> depth;
  for (const glm::uvec4& value : need) depth.push_back(std::bit_cast<float>(value.x));

  AnalysisOptions options;
  options.need8 = (flags & 1) != 0;
  options.depth = (flags & 2) != 0;
  options.centreWeight = (flags & 4) != 0;
  if (flags & 8) options.hotSpot = glm::vec2(static_cast<float>(flags >> 4), 3.5f);
  for (const glm::uvec4& value : need) decodeNeed(value, options.need8);
  neededPages(need, options.need8);
  analyzeNeedBuffer(need, depth, width, height, options);
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::needBuffer)
