#include "reference/oracle_roles.h"

#include "reference/recolor.h"
#include "reference/renderer.h"

namespace vt::reference {

void OracleResidentRenderer::draw(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                                  Frame& frame) const {
  renderFrame(mesh, everything_, settings, frame);
}

Frame OracleCacheRenderer::draw(const ClipSpaceMesh& mesh, const CacheState& cache,
                                const RenderSettings& settings) const {
  return renderFrame(mesh, cache, settings);
}

void OracleCacheRenderer::recolor(const Frame& drawn, std::span<const CacheState* const> caches,
                                  const RenderSettings& settings,
                                  std::span<std::vector<uint8_t>* const> colors) const {
  reference::recolor(drawn, caches, settings, colors);
}

}  // namespace vt::reference
