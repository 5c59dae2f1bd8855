#pragma once
// A page-priority heuristic (thesis 4.2) as the runtime uses it: the product of factors, parsed
// once from its text ("pixelsum", "pixelsum*noisevalue") when the configuration is read, so that
// no frame compares names. runtime/page_priority.h says what each factor measures.

#include <string>
#include <string_view>
#include <vector>

#include "common/enum_names.h"

namespace vt {

enum class PriorityFactor {
  kRandom,
  kPixelSum,
  kDistance,
  kWeightedPixel,
  kHotSpot,
  kNoiseValue,
  kMipGap
};

inline constexpr EnumNames<PriorityFactor, 7> kPriorityFactorNames = {{
    {PriorityFactor::kRandom, "random"},
    {PriorityFactor::kPixelSum, "pixelsum"},
    {PriorityFactor::kDistance, "distance"},
    {PriorityFactor::kWeightedPixel, "weightedpixel"},
    {PriorityFactor::kHotSpot, "hotspot"},
    {PriorityFactor::kNoiseValue, "noisevalue"},
    {PriorityFactor::kMipGap, "mipgap"},
}};

class Heuristic {
 public:
  Heuristic() = default;  // pixelsum

  // The factors joined by '*'. Throws std::invalid_argument: "heuristic: empty", or
  // "heuristic: 'speed' is not one of random, pixelsum, ...".
  static Heuristic parse(std::string_view text);

  // In the order written: the priority is their product, and inspection lists them so.
  const std::vector<PriorityFactor>& factors() const { return factors_; }
  bool uses(PriorityFactor factor) const;
  std::string text() const;  // the factors' names joined by '*'

  friend bool operator==(const Heuristic&, const Heuristic&) = default;

 private:
  std::vector<PriorityFactor> factors_{PriorityFactor::kPixelSum};
};

}  // namespace vt
