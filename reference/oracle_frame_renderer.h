#pragma once
// The oracle as a FrameRenderer (render/frame_renderer.h): renderFrame (renderer.h) over a cache
// state, or over every page resident straight from the file. Its delayed readback keeps the
// previous frame's needbuffer and depth and hands them out one frame late, as the GL path's
// pixel-buffer copies do.

#include <memory>
#include <vector>

#include "format/virtual_texture_reader.h"
#include "reference/texture_source.h"
#include "render/frame_renderer.h"

namespace vt::reference {

class OracleFrameRenderer : public FrameRenderer {
 public:
  // Reads `cache` at every draw: it must outlive the renderer.
  explicit OracleFrameRenderer(const CacheState& cache);
  // Every stored page of `reader` resident (ResidentTexture): `reader` must outlive the renderer.
  explicit OracleFrameRenderer(const VirtualTextureReader& reader);

  Frame render(const ClipSpaceMesh& mesh, const RenderSettings& settings,
               bool readDepth = false) override;
  Frame renderDelayed(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                      bool readDepth = false) override;
  void cacheChanged() override {}  // read at every draw
  void warmUp(const ClipSpaceMesh&, const RenderSettings&) override {}
  const CacheState* cache() const override { return cache_; }
  std::string describe(const RenderSettings& settings) const override;

 private:
  const CacheState* cache_ = nullptr;
  std::unique_ptr<const ResidentTexture> everything_;  // when cache_ is none
  // The previous renderDelayed's frame's needbuffer and depth.
  std::vector<glm::uvec4> delayedNeed_;
  std::vector<float> delayedDepth_;
};

}  // namespace vt::reference
