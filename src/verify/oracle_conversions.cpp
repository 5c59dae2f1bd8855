#include "verify/oracle_conversions.h"

#include "render/arithmetic_points.h"

namespace vt {

oracle::CacheState publicCacheState(const CacheState& cache) {
  oracle::CacheState state{false, cache.framesX, cache.framesY, {}};
  for (const uint64_t index : cache.residentPages) {
    const PageId page = fromAbsoluteIndex(index);
    const glm::u16vec4 entry = cache.indirection.entry(page);
    state.pages.push_back({page.level, page.x, page.y, entry.x, entry.y});
  }
  return state;
}

oracle::RenderOptions publicRenderOptions(const RenderSettings& settings,
                                          const std::string& modelFile) {
  oracle::RenderOptions options;
  options.modelFile = modelFile;
  if (modelFile.empty())
    options.profile = oracle::publicProfile(
        settings.model ? *settings.model
                       : pinnedModel(settings.arithmetic, arithmeticLabel(settings.arithmetic)));
  options.needEncoding =
      settings.need8 ? oracle::NeedEncoding::k8Bit : oracle::NeedEncoding::k32Bit;
  options.filtering =
      settings.trilinear ? oracle::Filtering::kTrilinear : oracle::Filtering::kBilinear;
  options.sampling =
      settings.exactFilter ? oracle::Sampling::kTexelFetch : oracle::Sampling::kHardwareLinear;
  options.threads = settings.threads;
  return options;
}

SetWidths verdictWidths(const oracle::Frame& frame) {
  const vt::ResultSets& sets = oracle::internalSets(frame);
  std::vector<glm::uvec4> need;
  if (sets.empty()) {
    need.reserve(frame.need.size() / 4);
    for (size_t i = 0; i + 3 < frame.need.size(); i += 4)
      need.emplace_back(frame.need[i], frame.need[i + 1], frame.need[i + 2], frame.need[i + 3]);
  }
  return setWidths(sets, need, frame.needEncoding == oracle::NeedEncoding::k8Bit);
}

}  // namespace vt
