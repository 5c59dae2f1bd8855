#pragma once
// Reduced needbuffers (as current engines render their feedback buffer): the needbuffer is drawn
// at 1/2^k of the screen's resolution per axis, its LOD compensated exactly in the shader
// (VtParameters::needScaleLog2), and jittered by a sub-pixel offset that changes every frame, so
// that over 4^k frames every screen pixel's page is sampled.

#include <cstdint>
#include <glm/glm.hpp>
#include <string>

#include "common/enum_names.h"
#include "scene/clip_space_mesh.h"

namespace vt {

// The needbuffer's viewport for a screen: each side divided by 2^k, at least 1.
Viewport reducedViewport(Viewport screen, int scaleLog2);

// The jitter of frame `frame`, in pixels of the reduced viewport, within (-1/2, 1/2)^2: the
// Halton sequence in bases 2 and 3 (k = 0: no jitter).
glm::vec2 needJitter(uint64_t frame, int scaleLog2);

// The scales by their written name: "1" -> k = 0, "2" -> 1, "4" -> 2, "8" -> 3.
inline constexpr EnumNames<int, 4> kNeedScaleNames = {{{0, "1"}, {1, "2"}, {2, "4"}, {3, "8"}}};

// Throws std::invalid_argument for a name not in kNeedScaleNames.
int parseNeedScale(const std::string& text);

}  // namespace vt
