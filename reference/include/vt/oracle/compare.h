#pragma once
// Compares a frame another renderer drew with the oracle's frame of the same inputs, pixel by
// pixel. A pixel is
//   identical    needbuffer and colour agree bit for bit;
//   flagged      otherwise, where the oracle marked it ambiguous (its result may change within
//                the profile's precision);
//   within bound the needbuffer agrees and no colour channel differs by more than the profile's
//                bound (llvmpipe 0, exact and nvidia 4 units of 8 bits);
//   mismatched   otherwise: a bug in one of the two renderers.

#include <cstdint>
#include <span>
#include <vector>

#include "vt/oracle/export.h"
#include "vt/oracle/render.h"

namespace vt::oracle {

struct PixelDifference {
  int x = 0, y = 0;               // window coordinates, y up
  uint32_t expectedNeed[4] = {};  // the oracle's
  uint32_t actualNeed[4] = {};
  uint8_t expectedColor[4] = {};
  uint8_t actualColor[4] = {};
};

struct Comparison {
  uint64_t pixels = 0, identical = 0, flagged = 0, withinBound = 0, mismatched = 0;
  uint64_t needMismatched = 0;              // mismatched pixels whose needbuffer differs
  int maxColorDifference = 0;               // over all pixels, 8-bit units
  double meanColorDifference = 0;           // over all channels of all pixels
  std::vector<PixelDifference> mismatches;  // the first 1000 mismatched pixels, row by row
  // For people, rows top to bottom, RGBA8: the colour difference times 16, and the class of each
  // pixel (black identical, green within bound, yellow flagged, red mismatched).
  std::vector<uint8_t> colorDifferenceImage, classificationImage;

  bool passed() const { return mismatched == 0; }
};

// `color` (RGBA8) and `need` (four per pixel, `oracle`'s encoding) are the other renderer's frame,
// rows bottom to top, of the oracle frame's size; throws Error otherwise.
VT_ORACLE_API Comparison compare(const Frame& oracle, std::span<const uint8_t> color,
                                 std::span<const uint32_t> need, Profile profile);

}  // namespace vt::oracle
