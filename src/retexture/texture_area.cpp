#include "retexture/texture_area.h"

#include <algorithm>

namespace vt {

TexelBounds faceTexelBounds(const TexturedScene& scene, const TexturedFace& face) {
  const SourceTexture& texture = scene.textures[face.texture];
  TexelBounds bounds{1e300, -1e300, 1e300, -1e300};
  for (uint32_t i = face.firstIndex; i < face.firstIndex + face.indexCount; ++i) {
    const glm::vec2 st = scene.uvs[scene.indices[i]];
    const double u = double{st.x} * texture.width, v = double{st.y} * texture.height;
    bounds.u0 = std::min(bounds.u0, u);
    bounds.u1 = std::max(bounds.u1, u);
    bounds.v0 = std::min(bounds.v0, v);
    bounds.v1 = std::max(bounds.v1, v);
  }
  return bounds;
}

std::vector<glm::vec2> retexturedUvs(const TexturedScene& scene, const Retexturing& layout) {
  std::vector<glm::vec2> uvs(scene.uvs.size(), glm::vec2(0.0f));
  const auto side = static_cast<double>(layout.side);
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const TexturedFace& face = scene.faces[f];
    const TextureArea& area = layout.areas[layout.faceArea[f]];
    const SourceTexture& texture = scene.textures[face.texture];
    const glm::i64vec2 shift = layout.faceShift.empty() ? glm::i64vec2(0) : layout.faceShift[f];
    // Integer parts first, exactly: only the fraction of s * w is rounded.
    const auto originX = static_cast<double>(shift.x - area.sourceX + static_cast<int64_t>(area.x));
    const auto originY = static_cast<double>(shift.y - area.sourceY + static_cast<int64_t>(area.y));
    for (uint32_t i = face.firstIndex; i < face.firstIndex + face.indexCount; ++i) {
      const uint32_t v = scene.indices[i];
      const glm::vec2 st = scene.uvs[v];
      const double u = double{st.x} * texture.width + originX;
      const double w = double{st.y} * texture.height + originY;
      uvs[v] = glm::vec2(static_cast<float>(u / side), static_cast<float>(w / side));
    }
  }
  return uvs;
}

}  // namespace vt
