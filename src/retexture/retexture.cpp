#include "retexture/retexture.h"

#include "retexture/chart_layout.h"
#include "retexture/page_grid_layout.h"

namespace vt {
namespace {

MethodResult measure(const TexturedScene& scene, Retexturing layout,
                     const RetextureOptions& options, std::vector<glm::vec2>& uvs) {
  uvs = retexturedUvs(scene, layout);
  MethodResult result;
  result.quality = measureLayout(scene, layout, uvs);
  if (options.measureCoherence)
    result.coherence = measureCoherence(scene, layout, uvs, options.coherence);
  result.layout = std::move(layout);
  return result;
}

}  // namespace

RetextureResult retexture(const TexturedScene& scene, const RetextureOptions& options) {
  RetextureResult result;
  std::vector<glm::vec2> baselineUvs, chartUvs;
  result.baseline = measure(scene, layoutOnPageGrid(scene, options.pageSize), options, baselineUvs);
  result.charts =
      measure(scene, layoutCharts(scene, options.pageSize, options.charts), options, chartUvs);
  result.uvs = options.method == "baseline" ? std::move(baselineUvs) : std::move(chartUvs);
  return result;
}

}  // namespace vt
