#pragma once
// Builds the result set of one pixel (result_set.h) under a precision model: the alternatives of
// every candidate triangle, each bounded by interval arithmetic over the model's parameters.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "reference/precision_model.h"
#include "reference/result_set.h"
#include "reference/triangle_setup.h"
#include "reference/visibility.h"

namespace vt::reference {

// The cache as the shader sees it, for the colour bounds.
class TexelSource {
 public:
  virtual ~TexelSource() = default;
  // Indirection entry (fx, fy, level of the resident page) of page (px, py) of level m.
  virtual glm::uvec4 entry(glm::ivec2 page, int level) = 0;
  // One cache texel, clamped to the cache's edge, 8-bit channels.
  virtual glm::u8vec4 texel(glm::ivec2 position) = 0;
};

// What the shader settings fix for every pixel.
struct SetShading {
  int pageSize = 128, border = 4, finestLevel = 0;
  bool trilinear = true, exactFilter = true;
  int needScaleLog2 = 0;
};

// What the oracle itself drew at the pixel: the index (set-up list) of the triangle it shows, -1
// for none, and that fragment's values.
struct OracleFragment {
  int32_t index = -1;
  glm::u8vec4 color{0};
  glm::vec2 uv{0.0f};
  int neededLevel = 0;
  float lod = 0;
};

// Appends the alternatives of pixel (px, py) to `out`. `candidates` are the set-up triangles whose
// boxes reach the pixel (Visibility::candidates).
void appendResultSet(const PrecisionModel& model, const SetShading& shading,
                     const std::vector<SetupTriangle>& triangles,
                     const std::vector<int32_t>& candidates, int px, int py, Viewport viewport,
                     DepthFormat depthFormat, const OracleFragment& oracle, TexelSource& source,
                     std::vector<Alternative>& out);

}  // namespace vt::reference
