#pragma once
// Compares a frame another renderer drew with the oracle's frame of the same inputs, pixel by
// pixel, under the precision model the oracle rendered with (DESIGN section 3, "Exactness").
//
// A pixel is
//   identical    needbuffer and colour agree bit for bit with the oracle's own value;
//   explained    otherwise, when some alternative of the pixel's result set (result_set.h) holds
//                the needbuffer value and every colour channel; counted by the parameter that
//                admits it (coverage, depth, attributes, lod, filter);
//   unexplained  otherwise: a bug in one of the two renderers, or a model too narrow. Each is
//                attributed to the parameter that would have to widen, and by how much.
// A pixel is ambiguous when its set holds more than one value; the ambiguous fraction says how
// much the model leaves open (0 under a pinned model such as llvmpipe).

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "render/frame.h"
#include "render/result_set.h"

namespace vt::reference {

inline constexpr size_t kListedMismatches = 1000;

// One unexplained pixel: the parameter that would have to widen to explain it, and by how much
// in that parameter's unit (widthUnit).
struct UnexplainedPixel {
  uint64_t index = 0;  // py * width + px, window y up
  int reason = 0;      // bit number of ResultReason
  double widenBy = 0;
};

// The unit `widenBy` is measured in, per reason: "pixel" (coverage: the centre's distance is not
// known, 1 means "a triangle more or less"), "depth" (1: another triangle in front), "pages" (at
// the observed level), "levels", "1/255" (colour).
const char* widthUnit(int reason);

struct FrameComparison {
  uint64_t pixels = 0, identical = 0, explained = 0, unexplained = 0, ambiguous = 0;
  std::array<uint64_t, kResultReasons> explainedBy{}, unexplainedBy{};
  std::array<double, kResultReasons> widenBy{};  // the largest widening each parameter needs
  uint64_t needMismatched = 0;                   // unexplained pixels whose needbuffer differs
  int maxColorDifference = 0;                    // over all pixels, 8-bit units
  double meanColorDifference = 0;                // over all channels of all pixels
  // The first kListedMismatches unexplained pixels, by rising index.
  std::vector<UnexplainedPixel> unexplainedPixels;
  // Images for people, rows top to bottom: the colour difference scaled by 16, and the class of
  // each pixel (black identical, a colour per reason for explained ones, red unexplained, grey
  // where identical but ambiguous).
  std::vector<uint8_t> colorDifferenceImage, classificationImage;

  bool passed() const { return unexplained == 0; }
};

// The classification image's colour for an explained reason (and red for unexplained).
glm::u8vec3 reasonShade(int reason);

// `color` (RGBA8) and `need` are the other renderer's frame in the oracle's row order (bottom to
// top), of the oracle frame's size; `need8` says the needbuffer's encoding.
FrameComparison compareFrames(const Frame& oracle, std::span<const uint8_t> color,
                              std::span<const glm::uvec4> need, bool need8);

// Adds another frame's counts (totals over frames; the listed pixels and images stay).
void accumulate(FrameComparison& total, const FrameComparison& frame);

}  // namespace vt::reference
