#pragma once
// How well a retexturing uses its texture (the thesis's "wasted space", 3.3.2.2):
// - pages allocated: pages of the finest level that some area touches (a sparse texture stores
//   only these), and of all levels together (their ancestors);
// - referenced fraction: texels of the allocated finest pages that some face's triangle touches
//   (conservatively: the texel's square overlaps the triangle in the new coordinates), over all
//   texels of those pages.

#include <cstdint>
#include <vector>

#include "retexture/texture_area.h"

namespace vt {

struct LayoutQuality {
  uint64_t finestPages = 0;
  uint64_t allPages = 0;
  uint64_t referencedTexels = 0;
  double referencedFraction = 0.0;
};

LayoutQuality measureLayout(const TexturedScene& scene, const Retexturing& layout,
                            const std::vector<glm::vec2>& uvs);

}  // namespace vt
