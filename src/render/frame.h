#pragma once
// What the oracle renders for one frame. Rows run bottom to top (window y up): pixel (px, py) is
// element py * width + px.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "render/result_set.h"
#include "scene/clip_space_mesh.h"

namespace vt {

struct Frame {
  Viewport viewport;
  std::vector<uint8_t> color;    // RGBA8; (0, 0, 0, 0) where no geometry
  std::vector<glm::uvec4> need;  // needbuffer; the encoding's "no geometry" value elsewhere
  std::vector<float> depth;      // window depth as stored; 1.0 where no geometry
  // Under a model that leaves a parameter free, every pixel's result set; empty under a pinned
  // model, where each pixel's set is the one value above.
  ResultSets sets;
  std::vector<int32_t> triangle;  // index of the mesh triangle shown, -1 where none
  // Debug channels, filled only when RenderSettings::debugChannels is set (empty otherwise):
  // texture coordinates, their fine derivatives, the lod, the resident level.
  std::vector<glm::vec2> uv;
  std::vector<glm::vec4> derivatives;  // (ds/dx, dt/dx, ds/dy, dt/dy)
  std::vector<float> lod;
  std::vector<int8_t> residentLevel;  // -1 where no geometry
};

}  // namespace vt
