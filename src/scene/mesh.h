#pragma once
// A triangle mesh in world space with virtual texture coordinates: what `vt retexture` writes and
// the renderers draw. World convention: right-handed, y up, units of the source scene.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace vt {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;     // per vertex: (s, t) in the virtual texture, t along its rows
  std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from the front
};

}  // namespace vt
