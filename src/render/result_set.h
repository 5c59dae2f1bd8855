#pragma once
// Per-pixel result sets (docs/design.md section 3, "Exactness"): under a precision model that
// leaves a parameter free, everything a conforming implementation could produce at a pixel.
//
// A pixel's set is a list of alternatives, one per triangle that may own the pixel (and one with
// no triangle where the pixel may stay empty). The oracle builds them
// (reference/result_set_builder.h); a comparison reads them (src/render/frame_comparison.h).

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace vt {

// The parameter that explains a difference (or that admitted an alternative).
enum ResultReason : uint8_t {
  kReasonCoverage = 1 << 0,    // sub-pixel precision and fill rule: which triangle, or none
  kReasonDepth = 1 << 1,       // depth precision: which of overlapping triangles is in front
  kReasonAttributes = 1 << 2,  // attribute interpolation (snapped vertices, arithmetic): the page
  kReasonLod = 1 << 3,         // derivatives, sqrt and log2: the needed level
  kReasonFilter = 1 << 4,      // sub-texel bits, filter weights, colour conversion: the colour
};
inline constexpr int kResultReasons = 5;
const char* reasonName(int bit);  // "coverage", "depth", "attributes", "lod", "filter"

// One way a conforming implementation may draw a pixel.
struct Alternative {
  int32_t triangle = -1;  // mesh triangle, -1: the pixel keeps the clear values
  uint8_t reasons = 0;    // why this triangle (coverage or depth); 0 for the oracle's own
  uint8_t levelLo = 0, levelHi = 0;      // needed levels
  glm::vec2 uvLo{0.0f}, uvHi{0.0f};      // (s, t) after the shader's clamp to [0, 1]
  glm::u8vec4 colorLo{0}, colorHi{0};    // every reachable colour
  glm::u8vec4 filterLo{0}, filterHi{0};  // from the oracle's (s, t) and LOD: filter only

  bool operator==(const Alternative&) const = default;
};

// The sets of a frame: pixel i's alternatives are alternatives[offsets[i] .. offsets[i + 1]).
// Empty when the model pins every parameter (every set is the frame's one value).
//
// Built against a judged frame (RenderSettings::judged), a pixel where that frame holds the
// oracle's own value has no alternative: it is identical, and no set is needed to say so. Every
// pixel's set holds at least one alternative otherwise (a triangle's, or the empty one).
struct ResultSets {
  std::vector<uint32_t> offsets;
  std::vector<Alternative> alternatives;
  bool judged = false;  // built only where the judged frame differs from the oracle's value
  bool empty() const { return offsets.empty(); }
  // Whether pixel i's set was built (always, unless `judged`).
  bool built(size_t pixel) const { return offsets[pixel + 1] != offsets[pixel]; }
  bool operator==(const ResultSets&) const = default;
};

// Whether the set of pixel i holds more than one value; false for a set not built.
bool ambiguous(const ResultSets& sets, size_t pixel);

}  // namespace vt
