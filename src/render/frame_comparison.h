#pragma once
// Compares a frame another renderer drew with the oracle's frame of the same inputs, pixel by
// pixel, under the precision model the oracle rendered with (docs/design.md section 3,
// "Exactness").
//
// A pixel is
//   identical    needbuffer and colour agree bit for bit with the oracle's own value;
//   explained    otherwise, when some alternative of the pixel's result set (result_set.h) holds
//                the needbuffer value and every colour channel; counted by the parameter that
//                admits it (coverage, depth, attributes, lod, filter);
//   unexplained  otherwise: a bug in one of the two renderers, or a model too narrow. Each is
//                attributed to the parameter that would have to widen, and by how much.
// A pixel is ambiguous when its set holds more than one value; the ambiguous fraction says how
// much the model leaves open (0 under a pinned model such as llvmpipe). Sets built against the
// compared frame (ResultSets::judged) exist only where it differs: ambiguity and the set widths
// below then count those pixels alone, and comparing another frame throws.

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "render/frame.h"
#include "render/result_set.h"

namespace vt {

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
// The same with the oracle frame's result sets held apart (`oracle.sets` is not read), so that a
// caller holding them elsewhere need not copy them into the frame.
FrameComparison compareFrames(const Frame& oracle, const ResultSets& sets,
                              std::span<const uint8_t> color, std::span<const glm::uvec4> need,
                              bool need8);

// Adds another frame's counts (totals over frames; the listed pixels and images stay).
void accumulate(FrameComparison& total, const FrameComparison& frame);

// How tight a verdict is: how much each covered pixel's result set admits, where the ambiguous
// fraction only counts the pixels that admit more than one value. A pixel is covered when some
// alternative of its set draws a triangle (under a pinned model, whose sets are empty: when the
// oracle's needbuffer names a page). Per covered pixel, each measure a marginal of the set (the
// needbuffer and the colour must still come from one alternative to pass):
//   colour width  per channel, the number of unorm8 values v that some alternative admits
//                 (colorLo <= v <= colorHi; the clear alternative admits 0 alone) minus one: hi -
//                 lo for one interval, 0 for one value, and a union of disjoint intervals counts
//                 only the values inside them. Averaged over the four channels, in units of 1/255.
//   levels        the number of needed levels m that some triangle's alternative admits
//                 (levelLo <= m <= levelHi).
//   pages         the number of distinct needbuffer values (px, py, m) that some triangle's
//                 alternative admits: at each of its levels m, the pages from (s, t) = uvLo to uvHi
//                 at level m, as compareFrames judges an observed page. "No geometry" is neither a
//                 level nor a page.
// The means are over covered pixels (a frame's background does not dilute them). Under a pinned
// model every covered pixel's set is the oracle's one value: width 0, one level, one page.
struct SetWidths {
  uint64_t covered = 0;      // covered pixels
  double colorWidthSum = 0;  // their colour widths (each the mean over channels), 1/255
  uint64_t levelSum = 0;     // their admitted levels
  uint64_t pageSum = 0;      // their admitted needbuffer values

  double meanColorWidth() const;
  double meanLevels() const;
  double meanPages() const;
  void add(const SetWidths& other);
};

// The widths of pixel `pixel`'s set (covered 0 or 1); nothing for empty (pinned) sets.
SetWidths pixelSetWidths(const ResultSets& sets, size_t pixel);

// A frame's widths: from its result sets, or, where they are empty (a pinned model), from the
// oracle's own needbuffer `need` (one value per covered pixel).
SetWidths setWidths(const ResultSets& sets, std::span<const glm::uvec4> need, bool need8);

}  // namespace vt
