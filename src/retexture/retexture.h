#pragma once
// `vt retexture` as a library call (thesis 3.3.2, "vtgeo"): lays out a textured scene twice, as
// the thesis does (page_grid_layout.h) and as we do (chart_layout.h), measures both
// (layout_quality.h, page_coherence.h) and keeps the chosen one's new coordinates.

#include <optional>
#include <string>

#include "retexture/face_charts.h"
#include "retexture/layout_quality.h"
#include "retexture/page_coherence.h"
#include "retexture/texture_area.h"

namespace vt {

struct RetextureOptions {
  uint32_t pageSize = 128;
  std::string method = "charts";  // "charts" (ours) or "baseline" (the thesis's)
  ChartOptions charts;
  bool measureCoherence = true;
  CoherenceSettings coherence;
};

struct MethodResult {
  Retexturing layout;
  LayoutQuality quality;
  std::optional<PageCoherence> coherence;
};

struct RetextureResult {
  MethodResult baseline, charts;
  const MethodResult& chosen(const RetextureOptions& options) const {
    return options.method == "baseline" ? baseline : charts;
  }
  std::vector<glm::vec2> uvs;  // the chosen method's new coordinates, per scene vertex
};

// Throws InputError naming the scene when a layout exceeds the format's limits.
RetextureResult retexture(const TexturedScene& scene, const RetextureOptions& options);

}  // namespace vt
