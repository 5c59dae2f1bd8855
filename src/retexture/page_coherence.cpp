#include "retexture/page_coherence.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "backends/backend.h"
#include "scene/camera.h"
#include "shader/needbuffer.h"

namespace vt {
std::vector<Camera> coherenceViews(const TexturedScene& scene) {
  std::vector<Camera> bases = scene.viewpoints;
  if (bases.empty()) {
    glm::vec3 low(INFINITY), high(-INFINITY);
    for (const glm::vec3& p : scene.positions) low = glm::min(low, p), high = glm::max(high, p);
    Camera camera;
    camera.position = 0.5f * (low + high);
    camera.target = camera.position + glm::vec3(0.0f, 0.0f, -1.0f);
    bases.push_back(camera);
  }
  std::vector<Camera> views;
  for (const Camera& base : bases)
    for (int quarter = 0; quarter < 4; ++quarter) {
      Camera view = base;
      const glm::mat4 turn =
          glm::rotate(glm::mat4(1.0f), glm::radians(90.0f * static_cast<float>(quarter)), base.up);
      view.target = base.position + glm::vec3(turn * glm::vec4(base.target - base.position, 0.0f));
      views.push_back(view);
    }
  return views;
}

PageCoherence measureCoherence(const TexturedScene& scene, const Retexturing& layout,
                               const std::vector<glm::vec2>& uvs,
                               const CoherenceSettings& settings) {
  TextureDescription description{.pageSize = layout.pageSize, .border = 1, .channels = 4};
  while (description.sideTexels() < layout.side) ++description.levelCount;
  const CacheState cache = rootOnlyCache(description);
  const Mesh mesh{scene.positions, uvs, scene.indices};
  RenderSettings render;
  render.viewport = {static_cast<int>(settings.width), static_cast<int>(settings.height)};
  render.threads = settings.threads;
  const std::unique_ptr<const CacheRenderer> oracle = makeCacheRenderer();
  PageCoherence coherence;
  double sumPer1000 = 0.0, sumPages = 0.0;
  uint32_t coveredViews = 0;
  for (const Camera& view : coherenceViews(scene)) {
    const Frame frame =
        oracle->draw(toClipSpace(mesh, view, render.viewport), cache, render);
    const NeededPages needed = neededPages(frame.need, false);
    ++coherence.views;
    if (needed.coveredPixels == 0) continue;
    ++coveredViews;
    const auto pages = static_cast<double>(needed.pages.size());
    sumPer1000 += 1000.0 * pages / static_cast<double>(needed.coveredPixels);
    sumPages += pages;
  }
  coherence.pagesPer1000Pixels = sumPer1000 / std::max(1u, coveredViews);
  coherence.meanPagesPerView = sumPages / std::max(1u, coveredViews);
  return coherence;
}

}  // namespace vt
