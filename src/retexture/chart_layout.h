#pragma once
// Our layout, fixing the two problems the thesis names (3.3.2.2): each chart (face_charts.h) gets
// only the texels its faces use plus a margin, not whole copies of the texture, and faces that
// touch in the mesh stay together in one area. Charts are packed on shelves without the page
// grid, in classes of 16 texels of height (tallest first) and, within a class, in Z-order of
// the charts' centroids in the scene (coherence between charts), each shelf filled left to right
// and closed when the next chart does not fit; the texture starts at the smallest side
// whose area holds all charts and doubles until they fit.

#include "retexture/face_charts.h"
#include "retexture/texture_area.h"

namespace vt {

// Throws InputError naming the scene when the texture would exceed the format's largest side.
Retexturing layoutCharts(const TexturedScene& scene, uint32_t pageSize,
                         const ChartOptions& options = {});

}  // namespace vt
