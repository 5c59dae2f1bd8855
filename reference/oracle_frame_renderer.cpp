#include "reference/oracle_frame_renderer.h"

#include <utility>

#include "reference/renderer.h"
#include "render/arithmetic_points.h"

namespace vt::reference {

OracleFrameRenderer::OracleFrameRenderer(const CacheState& cache) : cache_(&cache) {}

OracleFrameRenderer::OracleFrameRenderer(const VirtualTextureReader& reader)
    : everything_(std::make_unique<const ResidentTexture>(reader)) {}

Frame OracleFrameRenderer::render(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                                  bool readDepth) {
  Frame frame =
      cache_ ? renderFrame(mesh, *cache_, settings) : renderFrame(mesh, *everything_, settings);
  if (!readDepth) frame.depth = {};
  return frame;
}

Frame OracleFrameRenderer::renderDelayed(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                                         bool readDepth) {
  Frame frame = render(mesh, settings, readDepth);
  std::swap(frame.need, delayedNeed_);
  std::swap(frame.depth, delayedDepth_);
  return frame;
}

std::string OracleFrameRenderer::describe(const RenderSettings& settings) const {
  return "oracle, profile " + arithmeticLabel(settings.arithmetic);
}

}  // namespace vt::reference
