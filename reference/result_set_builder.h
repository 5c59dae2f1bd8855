#pragma once
// Builds the result set of one pixel (render/result_set.h) under a precision model: the
// alternatives of every candidate triangle. For each the oracle bounds, with interval arithmetic
// over the model's parameters (interval.h):
//   - the vertices: each within 2^-subpixelBits pixel of its float window position (snapping to
//     the model's sub-pixel grid), hence the barycentric coordinates at the pixel centre, the
//     coverage (sure, possible, impossible) and the window depth: by the affine map between the
//     moved and the nominal triangle (perturbed_triangle.h), which keeps these bounds first-order
//     tight; interval arithmetic over the corners only for triangles too small for it;
//   - (s, t) at the pixel, as the perspective-correct ratio of two interpolated planes, and the
//     fine derivatives over its 2x2 quad (helpers included) as differences of the same moved
//     planes (so their errors stay correlated, as on the hardware), each widened by the model's
//     float error of the evaluation;
//   - the LOD through sqrt and log2 with the model's errors, hence the needed levels;
//   - per channel the colour: the bilinear filter over every texel position (s, t) can reach on
//     every level the LOD can blend, each page looked up in the indirection table, widened by the
//     sub-texel and weight precision, blended over the reachable weights, and converted to 8 bits
//     as the model allows.
// Which triangle may own a pixel follows the GL rules on the candidates Embree gathers: it must
// possibly cover the centre and possibly pass GL_LESS against every candidate that surely covers.

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "reference/triangle_setup.h"
#include "reference/visibility.h"
#include "render/precision_model.h"
#include "render/result_set.h"

namespace vt::reference {

// The cache as the shader sees it, for the colour bounds.
class TexelSource {
 public:
  virtual ~TexelSource() = default;
  // Indirection entry (fx, fy, level of the resident page) of page (px, py) of level m.
  virtual glm::uvec4 entry(glm::ivec2 page, int level) = 0;
  // One cache texel, clamped to the cache's edge, 8-bit channels.
  virtual glm::u8vec4 texel(glm::ivec2 position) = 0;
  // The least and greatest value the texel may have when the block decoding is free
  // (PrecisionModel::decodingPinned false); its one value for texels that are not decoded.
  virtual std::array<glm::u8vec4, 2> texelRange(glm::ivec2 position) {
    const glm::u8vec4 v = texel(position);
    return {v, v};
  }
};

// What the shader settings fix for every pixel.
struct SetShading {
  int pageSize = 128, border = 4, finestLevel = 0;
  bool trilinear = true, exactFilter = true;
  int needScaleLog2 = 0;
  bool blockCompressed = false;  // the cache's texels are decoded from blocks
  double cacheSide = 0;  // the cache texture's larger side in texels (a sampler's coordinate bits)
};

// What the oracle itself drew at the pixel: the index (set-up list) of the triangle it shows, -1
// for none, and that fragment's values, its fine derivatives of (s, t) included.
struct OracleFragment {
  int32_t index = -1;
  glm::u8vec4 color{0};
  glm::vec2 uv{0.0f};
  int neededLevel = 0;
  float lod = 0;
  glm::vec2 dUVdx{0.0f}, dUVdy{0.0f};
};

// Builds pixels' result sets, one pixel at a time, for one frame's set-up triangles. What a
// candidate's moved corners bound (its snapping) is made once per builder, for every pixel of the
// tiles it builds. Not thread-safe; one builder per worker.
class ResultSetBuilder {
 public:
  ResultSetBuilder(const PrecisionModel& model, const SetShading& shading,
                   const std::vector<SetupTriangle>& triangles, Viewport viewport,
                   DepthFormat depthFormat, TexelSource& source);
  ~ResultSetBuilder();
  ResultSetBuilder(const ResultSetBuilder&) = delete;
  ResultSetBuilder& operator=(const ResultSetBuilder&) = delete;

  // Appends the alternatives of pixel (px, py) to `out`. `candidates` are those of the 4 x 4 block
  // that holds the pixel (Visibility::blockCandidates): the set-up triangles whose boxes reach it.
  void append(const Visibility::BlockCandidates& candidates, int px, int py,
              const OracleFragment& oracle, std::vector<Alternative>& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vt::reference
