#pragma once
// Compares a frame another renderer drew with the oracle's frame of the same inputs, pixel by
// pixel, under a precision profile (DESIGN section 3, "Exactness").
//
// A pixel is identical when needbuffer and colour agree bit for bit; otherwise it is flagged when
// the oracle marked it ambiguous (its result could change within the profile's precision), within
// bound when the needbuffer agrees and no colour channel differs by more than the profile's colour
// bound, and mismatched otherwise. Colour bounds in 8-bit units: llvmpipe 0 (the oracle matches it
// exactly), exact and nvidia 4 (the Khronos conformance threshold for 8-bit linear filtering:
// format bits minus 2).

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "reference/frame.h"
#include "reference/precision_profile.h"

namespace vt::reference {

int colorBound(PrecisionProfile profile);

inline constexpr size_t kListedMismatches = 1000;

struct FrameComparison {
  uint64_t pixels = 0, identical = 0, flagged = 0, withinBound = 0, mismatched = 0;
  uint64_t needMismatched = 0;     // unflagged pixels whose needbuffer differs
  int maxColorDifference = 0;      // over all pixels, 8-bit units
  double meanColorDifference = 0;  // over all channels of all pixels
  // The first kListedMismatches mismatched pixels, as indices in the oracle's row order
  // (py * width + px, window y up), rising.
  std::vector<uint64_t> mismatchedPixels;
  // Images for people, rows top to bottom: the colour difference scaled by 16, and the
  // classification (black identical, green within bound, yellow flagged, red mismatched).
  std::vector<uint8_t> colorDifferenceImage, classificationImage;
};

// `color` (RGBA8) and `need` are the other renderer's frame in the oracle's row order (bottom to
// top), of the oracle frame's size.
FrameComparison compareFrames(const Frame& oracle, std::span<const uint8_t> color,
                              std::span<const glm::uvec4> need, PrecisionProfile profile);

}  // namespace vt::reference
