#pragma once
// One hue per mip level, repeating after eight levels: the debug texture and the needbuffer images
// colour levels alike, so a needbuffer image can be read against the texture.

#include <array>
#include <cstdint>

namespace vt {

inline constexpr std::array<std::array<uint8_t, 3>, 8> kLevelHues = {{
    {230, 60, 60},
    {240, 150, 40},
    {220, 210, 50},
    {70, 190, 80},
    {50, 170, 200},
    {70, 90, 220},
    {160, 80, 210},
    {210, 90, 160},
}};

inline const std::array<uint8_t, 3>& levelHue(uint32_t level) {
  return kLevelHues[level % kLevelHues.size()];
}

}  // namespace vt
