#pragma once
// Charts: groups of faces that touch in the mesh and are textured continuously across where they
// meet, so one area of the virtual texture holds them together (our answer to the thesis's "no
// coherence", 3.3.2.2). Two faces are continuous when they have the same source texture, share a
// vertex position, and lie in one plane with one affine texture map (to 1/100 texel: brush faces
// that the map compiler split, T-junctions included) up to whole repetitions of the texture (a
// face joins with its coordinates shifted by them). Faces on different planes (two walls meeting
// at a corner) are never merged, even where their coordinates agree along the shared edge: their
// texels could overlap in the unrolled space, and each face keeps texels of its own. On one plane
// one affine map is one-to-one, so joined faces never share texels.
// Pairs are merged greedily in order of their face numbers, as long as the merged
// chart's texel rectangle stays within `slack` of the sum of the two charts' rectangles (an
// L-shaped union would otherwise waste the corner) and within `maxSide` texels per side.

#include <cstdint>
#include <vector>

#include "retexture/texture_area.h"

namespace vt {

struct ChartOptions {
  double slack = 0.10;       // merged area <= (1 + slack) * (area(a) + area(b))
  uint32_t maxSide = 4096;   // texels
  uint32_t margin = 1;       // source texels around what a chart's faces span (bilinear footprint)
  uint32_t columnPages = 4;  // width of the packing columns of chart_layout.h, in pages
};

struct Chart {
  uint32_t texture = 0;
  int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // unrolled texel rectangle [x0, x1) x [y0, y1)
  std::vector<uint32_t> faces;
  std::vector<glm::i64vec2> offsets;  // per face: texels added to its unrolled coordinates
  uint64_t width() const { return static_cast<uint64_t>(x1 - x0); }
  uint64_t height() const { return static_cast<uint64_t>(y1 - y0); }
};

// The texel rectangle of a face: its bounds rounded outwards, plus the margin; at least 1 x 1.
Chart faceChart(const TexturedScene& scene, uint32_t face, uint32_t margin);

// Charts in order of their first face; a chart's faces in the order they joined.
std::vector<Chart> buildCharts(const TexturedScene& scene, const ChartOptions& options);

}  // namespace vt
