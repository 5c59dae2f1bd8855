#include "reference/recolor.h"

#include <stdexcept>
#include <string>

#include "reference/parallel_for.h"
#include "reference/shader_backends.h"

namespace vt::reference {
namespace {

using Shader = shader::ShaderLogic<CacheBackend>;

// The indirection addresses a fragment reads (vtShadeFragment, src/shader/virtual_texture.glsl):
// with trilinear filtering the pages under it at levels floor(lod) and the next finer one (the
// same at the finest level), else the page at the needed level.
struct Lookups {
  PageId first, second;
};

Lookups lookupsOf(Shader& shader, glm::vec2 uvIn, glm::vec4 d,
                  const shader::VtParameters& p) {
  const shader::vec2 uv(shader.vtClampOrZero(uvIn.x, 1.0f), shader.vtClampOrZero(uvIn.y, 1.0f));
  const float lod = shader.vtLevelOfDetail(shader::vec2(d.x, d.y), shader::vec2(d.z, d.w), p);
  int first = shader.vtNeededLevel(lod), second = first;
  if (p.trilinear != 0) {
    first = static_cast<int>(std::floor(lod));
    second = first < p.finestLevel ? first + 1 : first;
  }
  const auto page = [&](int level) {
    const shader::ivec2 at = shader.vtPageAt(uv, level);
    return PageId{static_cast<uint32_t>(at.x), static_cast<uint32_t>(at.y),
                  static_cast<uint32_t>(level)};
  };
  return {page(first), page(second)};
}

// What decides a pixel's colour under one cache state, besides the pixel's own inputs.
struct ColourKey {
  glm::u16vec4 first, second;
  uint32_t width, height;
  bool operator==(const ColourKey&) const = default;
};

}  // namespace

void recolor(const Frame& drawn, std::span<const CacheState* const> caches,
             const RenderSettings& settings, std::span<std::vector<uint8_t>* const> colors) {
  const Viewport v = settings.viewport;
  const size_t pixels = static_cast<size_t>(v.width) * static_cast<size_t>(v.height);
  if (drawn.viewport.width != v.width || drawn.viewport.height != v.height ||
      drawn.uv.size() != pixels || drawn.derivatives.size() != pixels ||
      drawn.triangle.size() != pixels)
    throw std::invalid_argument("recolor: the frame was not drawn with debug channels at " +
                                std::to_string(v.width) + " x " + std::to_string(v.height));
  if (caches.size() != colors.size())
    throw std::invalid_argument("recolor: one colour buffer per cache state");
  if (caches.empty()) return;
  std::vector<shader::VtParameters> parameters;
  for (size_t k = 0; k < caches.size(); ++k) {
    colors[k]->resize(pixels * 4);
    parameters.push_back(shaderParameters(caches[k]->description,
                                          glm::vec2(static_cast<float>(caches[k]->widthTexels),
                                                    static_cast<float>(caches[k]->heightTexels)),
                                          settings));
  }
  // Without a border the footprint of a page's edge texels reaches the neighbouring frame,
  // which differs between cache states: then every state shades every pixel.
  const bool share = caches.size() > 1 && caches.front()->description.border >= 1;

  constexpr int kRows = 16;  // rows per task: enough work to outweigh the scheduling
  const int tasks = (v.height + kRows - 1) / kRows;
  parallelFor(static_cast<size_t>(tasks), settings.threads, [&](size_t task) {
    const DenormalMode denormals(settings.profile);
    std::vector<Shader> shaders;
    shaders.reserve(caches.size());
    for (const CacheState* cache : caches) shaders.emplace_back(cache, settings.profile);
    std::vector<std::pair<ColourKey, size_t>> shaded;  // this pixel's keys and who shaded them
    const int first = static_cast<int>(task) * kRows, last = std::min(v.height, first + kRows);
    for (size_t i = static_cast<size_t>(first) * static_cast<size_t>(v.width),
                end = static_cast<size_t>(last) * static_cast<size_t>(v.width);
         i < end; ++i) {
      if (drawn.triangle[i] < 0) {
        for (std::vector<uint8_t>* color : colors) std::fill_n(color->data() + i * 4, 4, 0);
        continue;
      }
      const glm::vec4 d = drawn.derivatives[i];
      Lookups lookups{};
      if (share) lookups = lookupsOf(shaders.front(), drawn.uv[i], d, parameters.front());
      shaded.clear();
      for (size_t k = 0; k < caches.size(); ++k) {
        uint8_t* out = colors[k]->data() + i * 4;
        if (share) {
          const CacheState& cache = *caches[k];
          const ColourKey key{cache.entry(lookups.first), cache.entry(lookups.second),
                              cache.widthTexels, cache.heightTexels};
          const auto same = std::find_if(shaded.begin(), shaded.end(),
                                         [&](const auto& entry) { return entry.first == key; });
          if (same != shaded.end()) {
            std::copy_n(colors[same->second]->data() + i * 4, 4, out);
            continue;
          }
          shaded.emplace_back(key, k);
        }
        const shader::VtFragment f = shaders[k].vtShadeFragment(
            drawn.uv[i], shader::vec2(d.x, d.y), shader::vec2(d.z, d.w), parameters[k]);
        for (int c = 0; c < 4; ++c) out[c] = toUnorm8(f.color[c]);
      }
    }
  });
}

void recolor(const Frame& drawn, const CacheState& cache, const RenderSettings& settings,
             std::vector<uint8_t>& color) {
  const CacheState* const caches[] = {&cache};
  std::vector<uint8_t>* const colors[] = {&color};
  recolor(drawn, caches, settings, colors);
}

}  // namespace vt::reference
