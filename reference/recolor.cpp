#include "reference/recolor.h"

#include <stdexcept>

#include "reference/parallel_for.h"
#include "reference/shader_backends.h"

namespace vt::reference {

void recolor(const Frame& drawn, const CacheState& cache, const RenderSettings& settings,
             std::vector<uint8_t>& color) {
  const Viewport v = settings.viewport;
  const size_t pixels = static_cast<size_t>(v.width) * static_cast<size_t>(v.height);
  if (drawn.viewport.width != v.width || drawn.viewport.height != v.height ||
      drawn.uv.size() != pixels || drawn.derivatives.size() != pixels ||
      drawn.triangle.size() != pixels)
    throw std::invalid_argument("recolor: the frame was not drawn with debug channels at " +
                                std::to_string(v.width) + " x " + std::to_string(v.height));
  color.resize(pixels * 4);
  const shader::VtParameters parameters = shaderParameters(
      cache.description,
      glm::vec2(static_cast<float>(cache.widthTexels), static_cast<float>(cache.heightTexels)),
      settings);
  constexpr int kRows = 16;  // rows per task: enough work to outweigh the scheduling
  const int tasks = (v.height + kRows - 1) / kRows;
  parallelFor(static_cast<size_t>(tasks), settings.threads, [&](size_t task) {
    const DenormalMode denormals(settings.profile);
    shader::ShaderLogic<CacheBackend> shader(&cache, settings.profile);
    const int first = static_cast<int>(task) * kRows, last = std::min(v.height, first + kRows);
    for (size_t i = static_cast<size_t>(first) * static_cast<size_t>(v.width),
                end = static_cast<size_t>(last) * static_cast<size_t>(v.width);
         i < end; ++i) {
      uint8_t* out = color.data() + i * 4;
      if (drawn.triangle[i] < 0) {
        out[0] = out[1] = out[2] = out[3] = 0;
        continue;
      }
      const glm::vec4 d = drawn.derivatives[i];
      const shader::VtFragment f = shader.vtShadeFragment(
          drawn.uv[i], shader::vec2(d.x, d.y), shader::vec2(d.z, d.w), parameters);
      for (int c = 0; c < 4; ++c) out[c] = toUnorm8(f.color[c]);
    }
  });
}

}  // namespace vt::reference
