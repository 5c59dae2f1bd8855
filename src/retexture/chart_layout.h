#pragma once
// Our layout, fixing the two problems the thesis names (3.3.2.2): each chart (face_charts.h) gets
// only the texels its faces use plus a margin, not whole copies of the texture, and faces that
// touch in the mesh stay together in one area. Charts are packed on shelves without the page
// grid. Coherence between charts comes from the scene's Z-order (of chart centroids): charts
// narrower than a column (ChartOptions::columnPages pages) fill columns of the texture one after
// the other on shelves, so charts that are near in the scene are near in the texture in both
// directions, and at coarser levels a view's faces share pages. Wider charts go first, on shelves
// across the whole texture, by height class of 16 texels (tallest first) and Z-order. The texture
// starts at the smallest side whose area holds all charts and doubles until they fit.

#include "retexture/face_charts.h"
#include "retexture/texture_area.h"

namespace vt {

// Throws InputError naming the scene when the texture would exceed the format's largest side.
Retexturing layoutCharts(const TexturedScene& scene, uint32_t pageSize,
                         const ChartOptions& options = {});

}  // namespace vt
