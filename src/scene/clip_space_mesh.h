#pragma once
// What both renderers draw: triangles of clip-space vertices with virtual texture coordinates,
// computed once on the CPU (docs/design.md section 3) and handed to the oracle and, unchanged, to
// the GL vertex shader. Draw order is the order of the triangles.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace vt {

struct ClipVertex {
  glm::vec4 position;  // clip space (x, y, z, w)
  glm::vec2 uv;        // virtual texture coordinates (s, t)
};

struct ClipSpaceMesh {
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;  // three per triangle
};

// The framebuffer: pixels (0, 0) .. (width - 1, height - 1), window y up (row 0 at the bottom).
struct Viewport {
  int width = 0;
  int height = 0;
};

}  // namespace vt
