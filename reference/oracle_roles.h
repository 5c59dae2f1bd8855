#pragma once
// The oracle in the roles only it plays (render/reference_roles.h): renderFrame (renderer.h) over
// every page of a texture or over a cache state, and recolor (recolor.h).

#include "format/virtual_texture_reader.h"
#include "reference/texture_source.h"
#include "render/reference_roles.h"

namespace vt::reference {

class OracleResidentRenderer : public ResidentRenderer {
 public:
  // `reader` must outlive the renderer.
  explicit OracleResidentRenderer(const VirtualTextureReader& reader) : everything_(reader) {}
  using ResidentRenderer::draw;
  void draw(const ClipSpaceMesh& mesh, const RenderSettings& settings, Frame& frame) const override;

 private:
  const ResidentTexture everything_;
};

class OracleCacheRenderer : public CacheRenderer {
 public:
  Frame draw(const ClipSpaceMesh& mesh, const CacheState& cache,
             const RenderSettings& settings) const override;
  void recolor(const Frame& drawn, std::span<const CacheState* const> caches,
               const RenderSettings& settings,
               std::span<std::vector<uint8_t>* const> colors) const override;
};

}  // namespace vt::reference
