#pragma once
// The one place where Quake 3's coordinates become the renderer's (mesh.h): Quake is right-handed
// with z up, x east, y north, in units of about an inch; ours is right-handed with y up, in metres.
// The map (x, y, z) -> (x, z, -y) is a rotation, so windings and handedness are kept.

#include <glm/glm.hpp>

namespace vt {

inline constexpr float kMetresPerQuakeUnit = 0.0254f;

inline glm::vec3 fromQuake(glm::vec3 quake) {
  return glm::vec3(quake.x, quake.z, -quake.y) * kMetresPerQuakeUnit;
}

// A direction (no scaling).
inline glm::vec3 directionFromQuake(glm::vec3 quake) {
  return glm::vec3(quake.x, quake.z, -quake.y);
}

// Quake 3's view height above a spawn point's origin (bg_public.h: DEFAULT_VIEWHEIGHT).
inline constexpr float kQuakeViewHeight = 26.0f;

}  // namespace vt
