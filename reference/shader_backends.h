#pragma once
// The shader's two views of the texture in the oracle (src/shader/shader_cpp.h instantiates the
// shared GLSL with one of them): every page resident, read from the file (golden images and
// reference frames), or a cache state as the GL renderer holds it. Also the framebuffer's
// conversion of a colour and the shader's uniform parameters, which every oracle pass shares.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

#include "reference/framebuffer_conversion.h"
#include "reference/linear_filter.h"
#include "reference/renderer.h"
#include "reference/shader_math.h"
#include "reference/texture_source.h"
#include "render/cache_state.h"
#include "shader/shader_cpp.h"

namespace vt::reference {

// The range decodeTexelRange gives texel (x, y) (in block coordinates modulo 4) of `block`.
inline std::array<glm::u8vec4, 2> rangeOf(PixelFormat format, const std::byte* block, int x,
                                          int y) {
  const std::array<BlockTexel, 2> r =
      decodeTexelRange(format, block, static_cast<uint32_t>((y % 4) * 4 + x % 4));
  return {glm::u8vec4(r[0][0], r[0][1], r[0][2], r[0][3]),
          glm::u8vec4(r[1][0], r[1][1], r[1][2], r[1][3])};
}

// The shader's view of a ResidentTexture: the indirection names the page (or its stored
// ancestor) in frame (0, 0) of a cache of one frame and remembers it; texel fetches read that
// page. The shader fetches texels only of the page it just looked up.
class ResidentBackend {
 public:
  ResidentBackend(const ResidentTexture* texture, const Arithmetic& arithmetic)
      : texture_(texture), arithmetic_(arithmetic) {}

  float log2(float x) { return log2Of(arithmetic_, x); }
  float sqrt(float x) { return arithmetic_.sqrt.of(x); }

  // Neighbouring fragments mostly look up pages a recent lookup named (trilinear filtering
  // alternates between two levels; a quad may straddle a page edge): those are remembered, so the
  // ancestor search and the shared page table (a lock) are needed only for a page not among the
  // last kRemembered.
  shader::uvec4 vtFetchIndirection(shader::ivec2 page, int level) {
    const PageId wanted{static_cast<uint32_t>(page.x), static_cast<uint32_t>(page.y),
                        static_cast<uint32_t>(level)};
    for (size_t k = 0; k < remembered_; ++k)
      if (recent_[k].wanted == wanted) {
        texels_ = recent_[k].texels;
        resident_ = recent_[k].resident;
        return shader::uvec4(0u, 0u, recent_[k].resident.level, 0u);
      }
    Lookup& slot = recent_[next_];
    next_ = (next_ + 1) % kRemembered;
    remembered_ = std::min(remembered_ + 1, kRemembered);
    slot.wanted = wanted;
    slot.resident = texture_->residentPage(wanted);
    slot.texels = texels_ = &texture_->texels(slot.resident, arithmetic_.blockDecoding);
    resident_ = slot.resident;
    return shader::uvec4(0u, 0u, slot.resident.level, 0u);
  }

  // The page the last lookup named, and making it current again: the lanes (lane_shading.h) look
  // up eight pages before they fetch from any.
  const void* currentPage() const { return texels_; }
  void usePage(const void* page) { texels_ = static_cast<const std::vector<std::byte>*>(page); }

  glm::u8vec4 fetch8(shader::ivec2 texel) const {
    const TextureDescription& d = texture_->description();
    const int side = static_cast<int>(d.storedPageSide());
    const int x = std::clamp(texel.x, 0, side - 1), y = std::clamp(texel.y, 0, side - 1);
    return expandToRgba(texels_->data() + (static_cast<size_t>(y) * side + x) * d.channels,
                        d.channels);
  }

  // What a free block decoding may make of a texel of the page the last scalar lookup named.
  std::array<glm::u8vec4, 2> fetchRange(shader::ivec2 texel) const {
    const TextureDescription& d = texture_->description();
    if (!isBlockCompressed(d.format)) return {fetch8(texel), fetch8(texel)};
    const int side = static_cast<int>(d.storedPageSide());
    const int x = std::clamp(texel.x, 0, side - 1), y = std::clamp(texel.y, 0, side - 1);
    const size_t block = static_cast<size_t>(y / 4) * static_cast<size_t>(side / 4) +
                         static_cast<size_t>(x / 4);
    return rangeOf(d.format, texture_->blocks(resident_).data() + block * blockBytes(d.format),
                   x, y);
  }

  shader::vec4 vtFetchCacheTexel(shader::ivec2 texel) {
    return unorm8ToFloat(fetch8(texel), arithmetic_.texelConversion);
  }

  shader::vec4 vtSampleCacheLinear(shader::vec2 texel) {
    const int side = static_cast<int>(texture_->description().storedPageSide());
    return sampleLinear([this](shader::ivec2 t) { return fetch8(t); }, texel, shader::ivec2(side),
                        arithmetic_.filter, arithmetic_.texelConversion);
  }

 private:
  const ResidentTexture* texture_;
  Arithmetic arithmetic_;
  struct Lookup {
    PageId wanted, resident;
    const std::vector<std::byte>* texels;
  };
  static constexpr size_t kRemembered = 4;
  std::array<Lookup, kRemembered> recent_{};
  size_t remembered_ = 0, next_ = 0;
  const std::vector<std::byte>* texels_ = nullptr;  // the last lookup's page
  PageId resident_;                                 // and its name
};

// The shader's view of a CacheState: the indirection table and the cache texture as uploaded.
class CacheBackend {
 public:
  CacheBackend(const CacheState* state, const Arithmetic& arithmetic)
      : state_(state), arithmetic_(arithmetic) {}

  float log2(float x) { return log2Of(arithmetic_, x); }
  float sqrt(float x) { return arithmetic_.sqrt.of(x); }

  shader::uvec4 vtFetchIndirection(shader::ivec2 page, int level) {
    const glm::u16vec4 e = state_->indirection.entry(PageId{static_cast<uint32_t>(page.x),
                                                            static_cast<uint32_t>(page.y),
                                                            static_cast<uint32_t>(level)});
    return shader::uvec4(e.x, e.y, e.z, e.w);
  }

  // Texel fetches do not depend on the last lookup.
  const void* currentPage() const { return nullptr; }
  void usePage(const void*) {}

  // The cache texture as RGBA8 rows, for reads of many texels at once (lane_shading.h).
  const uint8_t* texels() const { return state_->texels.data(); }
  int width() const { return static_cast<int>(state_->widthTexels); }
  int height() const { return static_cast<int>(state_->heightTexels); }

  const uint8_t* texelAt(shader::ivec2 texel) const {
    const int x = std::clamp(texel.x, 0, static_cast<int>(state_->widthTexels) - 1);
    const int y = std::clamp(texel.y, 0, static_cast<int>(state_->heightTexels) - 1);
    return state_->texels.data() +
           (static_cast<size_t>(y) * state_->widthTexels + static_cast<size_t>(x)) * 4;
  }

  glm::u8vec4 fetch8(shader::ivec2 texel) const {
    const uint8_t* t = texelAt(texel);
    return {t[0], t[1], t[2], t[3]};
  }

  // What a free block decoding may make of a cache texel (its one value in a texture that is not
  // block-compressed).
  std::array<glm::u8vec4, 2> fetchRange(shader::ivec2 texel) const {
    const TextureDescription& d = state_->description;
    if (!isBlockCompressed(d.format)) return {fetch8(texel), fetch8(texel)};
    const int x = std::clamp(texel.x, 0, static_cast<int>(state_->widthTexels) - 1);
    const int y = std::clamp(texel.y, 0, static_cast<int>(state_->heightTexels) - 1);
    const size_t block = static_cast<size_t>(y / 4) * (state_->widthTexels / 4) +
                         static_cast<size_t>(x / 4);
    return rangeOf(d.format, state_->blocks.data() + block * blockBytes(d.format), x, y);
  }

  shader::vec4 vtFetchCacheTexel(shader::ivec2 texel) {
    return arithmetic_.texelConversion == UnormConversion::kTimesReciprocal
               ? unorm8ToFloat(texelAt(texel))
               : unorm8ToFloat(fetch8(texel), arithmetic_.texelConversion);
  }

  shader::vec4 vtSampleCacheLinear(shader::vec2 texel) {
    return sampleLinear([this](shader::ivec2 t) { return fetch8(t); }, texel,
                        shader::ivec2(static_cast<int>(state_->widthTexels),
                                      static_cast<int>(state_->heightTexels)),
                        arithmetic_.filter, arithmetic_.texelConversion);
  }

 private:
  const CacheState* state_;
  Arithmetic arithmetic_;
};

// The shader's uniforms for texture `d`, a cache texture of `cacheSize` texels, and `settings`.
inline shader::VtParameters shaderParameters(const TextureDescription& d, glm::vec2 cacheSize,
                                             const RenderSettings& settings) {
  shader::VtParameters parameters{};
  parameters.pageSize = static_cast<int>(d.pageSize);
  parameters.border = static_cast<int>(d.border);
  parameters.finestLevel = static_cast<int>(d.finestLevel());
  parameters.trilinear = settings.trilinear ? 1 : 0;
  parameters.exactFilter = settings.exactFilter ? 1 : 0;
  parameters.need8 = settings.need8 ? 1 : 0;
  parameters.needScaleLog2 = settings.needScaleLog2;
  parameters.cacheSize = cacheSize;
  return parameters;
}

}  // namespace vt::reference
