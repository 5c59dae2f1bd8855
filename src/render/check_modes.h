#pragma once
// The two ways a crosscheck draws every view (`vt crosscheck`, `vt-capture scenes`): texel fetches
// with manual trilinear filtering into a 32-bit needbuffer, and the sampler's GL_LINEAR bilinear
// into an 8-bit needbuffer where the texture's levels fit that encoding.

#include <cstdint>
#include <vector>

#include "render/render_settings.h"
#include "shader/needbuffer.h"

namespace vt {

struct CheckMode {
  const char* name;
  bool exactFilter, trilinear, need8;
};

inline void applyMode(RenderSettings& settings, const CheckMode& mode) {
  settings.exactFilter = mode.exactFilter;
  settings.trilinear = mode.trilinear;
  settings.need8 = mode.need8;
}

inline std::vector<CheckMode> checkModes(uint32_t finestLevel) {
  std::vector<CheckMode> modes = {{"texelfetch-trilinear-need32", true, true, false},
                                  {"linear-bilinear-need8", false, false, true}};
  if (!need8Encodes(finestLevel)) modes.pop_back();
  return modes;
}

}  // namespace vt
