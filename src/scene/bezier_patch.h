#pragma once
// Tessellation of Quake 3 patch surfaces: a control grid of (2n+1) x (2m+1) points is n x m
// biquadratic Bezier patches sharing their edge rows and columns. Each patch is evaluated on a
// regular (level+1) x (level+1) grid of parameter values, positions and texture coordinates with
// the same Bernstein weights, and adjacent patches share their edge vertices, so the result is one
// watertight grid of (n * level + 1) x (m * level + 1) vertices.

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace vt {

// Subdivisions per patch and direction used by `vt retexture` (Quake 3 itself picks the level per
// patch from its curvature; a fixed level keeps the output independent of any view).
inline constexpr int kPatchTessellationLevel = 8;

struct TessellatedPatch {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> st;
  std::vector<uint32_t> indices;  // three per triangle; winding as the control grid's rows give it
};

// `positions` and `st` hold width * height control points, row by row (width along a row).
// Requires odd width, height >= 3 and level >= 1 (std::invalid_argument otherwise).
TessellatedPatch tessellatePatch(std::span<const glm::vec3> positions,
                                 std::span<const glm::vec2> st, int width, int height, int level);

}  // namespace vt
