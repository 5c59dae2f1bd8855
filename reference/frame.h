#pragma once
// What the oracle renders for one frame. Rows run bottom to top (window y up): pixel (px, py) is
// element py * width + px.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "scene/clip_space_mesh.h"

namespace vt::reference {

// Why a pixel's result could differ on the target within the profile's documented precision.
enum AmbiguityReason : uint8_t {
  kNearEdge = 1 << 0,        // pixel centre within 1/256 pixel of an edge of the shown triangle
  kNearlyCoplanar = 1 << 1,  // another covering triangle's depth within the depth tolerance
  kPageBoundary = 1 << 2,    // s * 2^m or t * 2^m within 4 ulps of an integer
  kLevelBoundary = 1 << 3,   // lod within 2^-12 of an integer (the needed level could change)
  kNearZeroW = 1 << 4,       // |w| below 1e-6 at a quad pixel
};

struct Frame {
  Viewport viewport;
  std::vector<uint8_t> color;      // RGBA8; (0, 0, 0, 0) where no geometry
  std::vector<glm::uvec4> need;    // needbuffer; the encoding's "no geometry" value elsewhere
  std::vector<float> depth;        // window depth as stored; 1.0 where no geometry
  std::vector<uint8_t> ambiguity;  // AmbiguityReason bits
  std::vector<int32_t> triangle;   // index of the mesh triangle shown, -1 where none
  // Debug channels, filled only when RenderSettings::debugChannels is set (empty otherwise):
  // texture coordinates, their fine derivatives, the lod, the resident level.
  std::vector<glm::vec2> uv;
  std::vector<glm::vec4> derivatives;  // (ds/dx, dt/dx, ds/dy, dt/dy)
  std::vector<float> lod;
  std::vector<int8_t> residentLevel;  // -1 where no geometry
};

}  // namespace vt::reference
