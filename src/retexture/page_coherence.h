#pragma once
// The coherence figure of a retexturing (the thesis's "no coherence", 3.3.2.2): the mean number
// of distinct pages the needbuffer requests per 1,000 covered screen pixels, over a fixed set of
// views. Fewer pages for the same pixels means neighbouring faces share pages, so less is
// streamed. Views: each viewpoint of the scene looking in four directions 90 degrees apart
// (the first its own); a scene without viewpoints is looked at from its bounding box's centre.
// Needbuffers come from the oracle (32-bit encoding, trilinear's needed level).

#include <cstdint>
#include <vector>

#include "retexture/texture_area.h"

namespace vt {

struct CoherenceSettings {
  uint32_t width = 640, height = 360;
  unsigned threads = 0;  // 0: every core
};

struct PageCoherence {
  uint32_t views = 0;
  double pagesPer1000Pixels = 0.0;  // mean over the views that cover any pixel
  double meanPagesPerView = 0.0;    // likewise
};

// The views the figure uses (also for the report).
std::vector<Camera> coherenceViews(const TexturedScene& scene);

PageCoherence measureCoherence(const TexturedScene& scene, const Retexturing& layout,
                               const std::vector<glm::vec2>& uvs,
                               const CoherenceSettings& settings = {});

}  // namespace vt
