#include "cli/oracle_conversions.h"

#include "reference/api/api_internal.h"

namespace vt {

oracle::Scene publicScene(const ClipSpaceMesh& mesh, Viewport viewport) {
  oracle::Scene scene{{viewport.width, viewport.height}, {}, mesh.indices};
  scene.vertices.reserve(mesh.vertices.size());
  for (const ClipVertex& v : mesh.vertices)
    scene.vertices.push_back(
        {v.position.x, v.position.y, v.position.z, v.position.w, v.uv.x, v.uv.y});
  return scene;
}

oracle::CacheState publicCacheState(const reference::CacheState& cache) {
  oracle::CacheState state{false, cache.framesX, cache.framesY, {}};
  for (const uint64_t index : cache.residentPages) {
    const PageId page = fromAbsoluteIndex(index);
    const glm::u16vec4 entry = cache.entry(page);
    state.pages.push_back({page.level, page.x, page.y, entry.x, entry.y});
  }
  return state;
}

oracle::RenderOptions publicRenderOptions(const reference::RenderSettings& settings) {
  oracle::RenderOptions options;
  options.profile = oracle::publicProfile(settings.profile);
  options.needEncoding =
      settings.need8 ? oracle::NeedEncoding::k8Bit : oracle::NeedEncoding::k32Bit;
  options.filtering =
      settings.trilinear ? oracle::Filtering::kTrilinear : oracle::Filtering::kBilinear;
  options.sampling =
      settings.exactFilter ? oracle::Sampling::kTexelFetch : oracle::Sampling::kHardwareLinear;
  options.threads = settings.threads;
  return options;
}

std::vector<uint32_t> flatNeed(std::span<const glm::uvec4> need) {
  std::vector<uint32_t> flat;
  flat.reserve(need.size() * 4);
  for (const glm::uvec4& v : need) flat.insert(flat.end(), {v.x, v.y, v.z, v.w});
  return flat;
}

}  // namespace vt
