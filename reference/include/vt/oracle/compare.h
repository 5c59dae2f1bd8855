#pragma once
// Compares a frame another renderer drew with the oracle's frame of the same inputs, pixel by
// pixel, under the precision model the oracle frame was rendered with. A pixel is
//   identical    needbuffer and colour agree bit for bit with the oracle's value;
//   explained    otherwise, when the pixel's result set (every value a conforming implementation
//                could produce under the model) holds it; counted by the model parameter that
//                admits it;
//   unexplained  otherwise: a bug in one of the two renderers, or a model too narrow; each names
//                the parameter that would have to widen, and by how much.
// The ambiguous count (pixels whose set holds more than one value) says how much the model leaves
// open: 0 under exact and llvmpipe, whose every set is one value.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vt/oracle/export.h"
#include "vt/oracle/render.h"

namespace vt::oracle {

// The model parameters a difference is explained by, or would need: 0 coverage (sub-pixel
// precision, fill rule), 1 depth, 2 attributes (the page), 3 lod (the level), 4 filter (colour).
inline constexpr int kReasons = 5;
VT_ORACLE_API std::string reasonName(int reason);  // "coverage", "depth", ...
// The unit of a widening per reason: "triangle", "triangle", "pages", "levels", "1/255".
VT_ORACLE_API std::string widthUnit(int reason);

struct PixelDifference {
  int x = 0, y = 0;               // window coordinates, y up
  uint32_t expectedNeed[4] = {};  // the oracle's
  uint32_t actualNeed[4] = {};
  uint8_t expectedColor[4] = {};
  uint8_t actualColor[4] = {};
  int reason = 0;      // the parameter that would have to widen
  double widenBy = 0;  // by this much, in widthUnit(reason)
};

struct Comparison {
  uint64_t pixels = 0, identical = 0, explained = 0, unexplained = 0, ambiguous = 0;
  std::array<uint64_t, kReasons> explainedBy{}, unexplainedBy{};
  std::array<double, kReasons> widenBy{};   // the largest widening each parameter would need
  uint64_t needMismatched = 0;              // unexplained pixels whose needbuffer differs
  int maxColorDifference = 0;               // over all pixels, 8-bit units
  double meanColorDifference = 0;           // over all channels of all pixels
  std::string model;                        // the model that judged
  // The sets were built against this frame (RenderOptions' judged frame): only where it differs,
  // so `ambiguous` counts those pixels alone.
  bool judged = false;
  std::vector<PixelDifference> mismatches;  // the first 1000 unexplained pixels, row by row
  // For people, rows top to bottom, RGBA8: the colour difference times 16, and the class of each
  // pixel (black identical, grey identical but ambiguous, per reason explained: blue coverage,
  // cyan depth, green attributes, yellow lod, violet filter; red unexplained).
  std::vector<uint8_t> colorDifferenceImage, classificationImage;

  bool passed() const { return unexplained == 0; }
};

// `color` (RGBA8) and `need` (four per pixel, `oracle`'s encoding) are the other renderer's frame,
// rows bottom to top, of the oracle frame's size; throws Error otherwise.
VT_ORACLE_API Comparison compare(const Frame& oracle, std::span<const uint8_t> color,
                                 std::span<const uint32_t> need);

}  // namespace vt::oracle
