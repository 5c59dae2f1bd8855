#pragma once
// Random textured triangles for the GL shading tests: magnified, minified and grazing, some
// clipped (w from 0.4 to 4, corners up to 1.8 outside the view), each with texture coordinates
// spread 0.02, 0.2 or 0.6 around a random centre inside [0, 1].

#include <glm/glm.hpp>
#include <random>

#include "common/random_draws.h"
#include "reference/renderer.h"

namespace vt::test {

inline void appendRandomTriangles(ClipSpaceMesh& mesh, std::mt19937& random, int count) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), wRange(0.4f, 4.0f);
  for (int k = 0; k < count; ++k) {
    const float spread = k % 4 == 0 ? 0.02f : (k % 4 == 1 ? 0.2f : 0.6f);
    const glm::vec2 centre = 0.5f + 0.45f * drawPoint([&] { return unit(random); });
    const glm::vec2 xy = drawPoint([&] { return unit(random); });
    for (int corner = 0; corner < 3; ++corner) {
      const float w = wRange(random);
      const glm::vec2 p = xy + 0.8f * drawPoint([&] { return unit(random); });
      mesh.vertices.push_back(
          {{p.x * w, p.y * w, 0.9f * unit(random) * w, w},
           glm::clamp(centre + spread * drawPoint([&] { return unit(random); }), 0.0f, 1.0f)});
      mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
    }
  }
}

}  // namespace vt::test
