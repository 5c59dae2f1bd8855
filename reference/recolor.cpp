#include "reference/recolor.h"

#include <algorithm>
#include <array>
#include <bit>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/parallel_for.h"
#include "reference/shader_backends.h"
#include "reference/shader_math.h"

namespace vt::reference {
namespace {

using Shader = shader::ShaderLogic<CacheBackend>;

// The indirection addresses a fragment reads (vtShadeFragment, src/shader/virtual_texture.glsl):
// with trilinear filtering the pages under it at levels floor(lod) and the next finer one (the
// same at the finest level), else the page at the needed level.
struct Lookups {
  PageId first, second;
  shader::vec2 uv;  // clamped to [0, 1], as the shader clamps it
};

Lookups lookupsOf(Shader& shader, glm::vec2 uvIn, glm::vec4 d, const shader::VtParameters& p) {
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
  return {page(first), page(second), uv};
}

// What decides a pixel's colour under one cache state, besides the pixel's own inputs (its
// texture coordinates and LOD, hence the blend weight): the two indirection entries (the same
// pages in the same frames), or under float filtering (exactFilter), per lookup, the page read
// (its level; the address is the pixel's) and the filter's inputs in vtBilinearExact: the
// footprint's first texel relative to the frame's origin and the fractions, bit for bit. Frames
// at different places in the cache give the same inputs wherever their origins round the texel
// position alike, which most do. The entries are compared first: they cost two reads.
struct ColourKey {
  std::array<uint32_t, 10> words{};
  uint32_t width = 0, height = 0;
  bool operator==(const ColourKey&) const = default;
};

// The filter inputs of one lookup into `key` from word `at` on: the resident level, the footprint
// relative to the frame, the fractions. The arithmetic is vtCacheTexel's (through the shader) and
// vtBilinearExact's first three lines (src/shader/virtual_texture.glsl).
void addFilterInputs(ColourKey& key, size_t at, Shader& shader, shader::vec2 uv, PageId page,
                     glm::u16vec4 entry, const shader::VtParameters& p) {
  const shader::uvec4 e(entry.x, entry.y, entry.z, entry.w);
  const shader::ivec2 address(static_cast<int>(page.x), static_cast<int>(page.y));
  const shader::vec2 texel = shader.vtCacheTexel(uv, address, static_cast<int>(page.level), e, p);
  const shader::vec2 t = texel - shader::vec2(0.5f, 0.5f);
  const shader::vec2 base = glm::floor(t);
  const shader::vec2 f = t - base;
  const int stored = p.pageSize + 2 * p.border;
  const shader::ivec2 origin(static_cast<int>(entry.x) * stored,
                             static_cast<int>(entry.y) * stored);
  const shader::ivec2 relative = shader::ivec2(base) - origin;
  key.words[at] = entry.z;
  key.words[at + 1] = static_cast<uint32_t>(relative.x);
  key.words[at + 2] = static_cast<uint32_t>(relative.y);
  key.words[at + 3] = std::bit_cast<uint32_t>(f.x);
  key.words[at + 4] = std::bit_cast<uint32_t>(f.y);
}

ColourKey colourKey(Shader& shader, const CacheState& cache, shader::vec2 uv,
                    const Lookups& lookups, const shader::VtParameters& p) {
  ColourKey key;
  key.width = cache.widthTexels;
  key.height = cache.heightTexels;
  addFilterInputs(key, 0, shader, uv, lookups.first, cache.indirection.entry(lookups.first), p);
  addFilterInputs(key, 5, shader, uv, lookups.second, cache.indirection.entry(lookups.second), p);
  return key;
}

// The indirection entries a pixel reads, and the cache's size.
struct EntryPair {
  glm::u16vec4 first, second;
  uint32_t width, height;
  bool operator==(const EntryPair&) const = default;
};

// A state that shaded the pixel itself and the filter inputs it read (when computed).
struct Shaded {
  std::optional<ColourKey> key;
  size_t state;
};

bool operator==(const Lookups& a, const Lookups& b) {
  return a.first == b.first && a.second == b.second;
}

// The indirection entries each state reads for the pixel's lookups, and for each state the first
// state that reads the same ones (itself when none before it does): neighbouring pixels mostly
// look up the same pages, so the entries are read, and the states grouped, once per run of such
// pixels rather than once per pixel (the tables are large and their reads miss the caches).
class EntryGroups {
 public:
  explicit EntryGroups(std::span<const CacheState* const> caches)
      : caches_(caches), entries_(caches.size()), first_(caches.size()) {}

  void lookUp(const Lookups& lookups) {
    if (valid_ && lookups == lookups_) return;
    lookups_ = lookups;
    valid_ = true;
    for (size_t k = 0; k < caches_.size(); ++k) {
      const CacheState& cache = *caches_[k];
      entries_[k] = {cache.indirection.entry(lookups.first),
                     cache.indirection.entry(lookups.second), cache.widthTexels,
                     cache.heightTexels};
      first_[k] = k;
      for (size_t j = 0; j < k; ++j)
        if (first_[j] == j && entries_[j] == entries_[k]) {
          first_[k] = j;
          break;
        }
    }
  }

  // The first state that reads what state k reads.
  size_t firstOf(size_t k) const { return first_[k]; }

 private:
  std::span<const CacheState* const> caches_;
  std::vector<EntryPair> entries_;
  std::vector<size_t> first_;
  Lookups lookups_{};
  bool valid_ = false;
};

// Pixel i of a frame with geometry there, shaded from its recorded inputs under the shader's cache
// state, into out[0..3].
void shadePixel(Shader& shader, const Frame& drawn, size_t i,
                const shader::VtParameters& parameters, const RenderSettings& settings,
                uint8_t* out) {
  const glm::vec4 d = drawn.derivatives[i];
  const Shader::VtFragment f = shader.vtShadeFragment(drawn.uv[i], shader::vec2(d.x, d.y),
                                                      shader::vec2(d.z, d.w), parameters);
  for (int c = 0; c < 4; ++c) out[c] = toUnorm8(f.color[c], settings.arithmetic.colourConversion);
}

void requireDebugChannels(const Frame& drawn, Viewport v) {
  const size_t pixels = static_cast<size_t>(v.width) * static_cast<size_t>(v.height);
  if (drawn.viewport.width != v.width || drawn.viewport.height != v.height ||
      drawn.uv.size() != pixels || drawn.derivatives.size() != pixels ||
      drawn.triangle.size() != pixels)
    throw std::invalid_argument("recolor: the frame was not drawn with debug channels at " +
                                std::to_string(v.width) + " x " + std::to_string(v.height));
}

}  // namespace

void recolor(const Frame& drawn, std::span<const CacheState* const> caches,
             const RenderSettings& settings, std::span<std::vector<uint8_t>* const> colors) {
  const Viewport v = settings.viewport;
  const size_t pixels = static_cast<size_t>(v.width) * static_cast<size_t>(v.height);
  requireDebugChannels(drawn, v);
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
  // which differs between cache states: then every state shades every pixel. The key's
  // footprint is the page's own only within its frame: borders of one texel or more.
  const bool share = caches.size() > 1 && caches.front()->description.border >= 1;

  constexpr int kRows = 16;  // rows per task: enough work to outweigh the scheduling
  const int tasks = (v.height + kRows - 1) / kRows;
  parallelFor(static_cast<size_t>(tasks), settings.threads, [&](size_t task) {
    const DenormalMode denormals(settings.arithmetic.flushDenormals);
    std::vector<Shader> shaders;
    shaders.reserve(caches.size());
    for (const CacheState* cache : caches) shaders.emplace_back(cache, settings.arithmetic);
    EntryGroups groups(caches);
    std::vector<Shaded> shaded;  // the states that shaded this pixel themselves
    const int first = static_cast<int>(task) * kRows, last = std::min(v.height, first + kRows);
    for (size_t i = static_cast<size_t>(first) * static_cast<size_t>(v.width),
                end = static_cast<size_t>(last) * static_cast<size_t>(v.width);
         i < end; ++i) {
      if (drawn.triangle[i] < 0) {
        for (std::vector<uint8_t>* color : colors) std::fill_n(color->data() + i * 4, 4, 0);
        continue;
      }
      Lookups lookups{};
      if (share) {
        lookups = lookupsOf(shaders.front(), drawn.uv[i], drawn.derivatives[i], parameters.front());
        groups.lookUp(lookups);
      }
      shaded.clear();
      for (size_t k = 0; k < caches.size(); ++k) {
        uint8_t* out = colors[k]->data() + i * 4;
        if (share) {
          // The same entries as an earlier state: the same frames, the same colour (that state's
          // colour is written: it comes first). Else the same filter inputs as a state that
          // shaded the pixel, from frames elsewhere in the cache.
          const size_t same = groups.firstOf(k);
          if (same != k) {
            std::copy_n(colors[same]->data() + i * 4, 4, out);
            continue;
          }
          std::optional<ColourKey> key;
          if (parameters[k].exactFilter != 0) {
            key = colourKey(shaders[k], *caches[k], lookups.uv, lookups, parameters[k]);
            const auto match = std::find_if(shaded.begin(), shaded.end(), [&](const Shaded& s) {
              return s.key && *s.key == *key;
            });
            if (match != shaded.end()) {
              std::copy_n(colors[match->state]->data() + i * 4, 4, out);
              continue;
            }
          }
          shaded.push_back({key, k});
        }
        shadePixel(shaders[k], drawn, i, parameters[k], settings, out);
      }
    }
  });
}

void recolorPixels(const Frame& drawn, const CacheState& cache, const RenderSettings& settings,
                   std::span<const uint32_t> pixels, std::span<uint8_t> rgba) {
  const Viewport v = settings.viewport;
  const size_t count = static_cast<size_t>(v.width) * static_cast<size_t>(v.height);
  requireDebugChannels(drawn, v);
  if (rgba.size() != pixels.size() * 4)
    throw std::invalid_argument("recolorPixels: four bytes per pixel listed");
  const DenormalMode denormals(settings.arithmetic.flushDenormals);
  Shader shader(&cache, settings.arithmetic);
  const shader::VtParameters parameters = shaderParameters(
      cache.description,
      glm::vec2(static_cast<float>(cache.widthTexels), static_cast<float>(cache.heightTexels)),
      settings);
  for (size_t k = 0; k < pixels.size(); ++k) {
    const size_t i = pixels[k];
    if (i >= count) throw std::invalid_argument("recolorPixels: a pixel outside the frame");
    uint8_t* out = rgba.data() + k * 4;
    if (drawn.triangle[i] < 0)
      std::fill_n(out, 4, 0);
    else
      shadePixel(shader, drawn, i, parameters, settings, out);
  }
}

std::vector<PagesRead> pagesRead(const Frame& drawn, const TextureDescription& description,
                                 const RenderSettings& settings) {
  const Viewport v = settings.viewport;
  requireDebugChannels(drawn, v);
  std::vector<PagesRead> pages(static_cast<size_t>(v.width) * static_cast<size_t>(v.height));
  // What a pixel reads depends on the cache's size only through parameters no lookup uses.
  const shader::VtParameters parameters = shaderParameters(description, glm::vec2(1.0f), settings);
  constexpr int kRows = 16;
  const int tasks = (v.height + kRows - 1) / kRows;
  parallelFor(static_cast<size_t>(tasks), settings.threads, [&](size_t task) {
    const DenormalMode denormals(settings.arithmetic.flushDenormals);
    Shader shader(nullptr, settings.arithmetic);  // the lookups read no texel and no entry
    const int first = static_cast<int>(task) * kRows, last = std::min(v.height, first + kRows);
    for (size_t i = static_cast<size_t>(first) * static_cast<size_t>(v.width),
                end = static_cast<size_t>(last) * static_cast<size_t>(v.width);
         i < end; ++i) {
      if (drawn.triangle[i] < 0) continue;
      const Lookups lookups = lookupsOf(shader, drawn.uv[i], drawn.derivatives[i], parameters);
      pages[i] = {lookups.first, lookups.second, true};
    }
  });
  return pages;
}

void recolor(const Frame& drawn, const CacheState& cache, const RenderSettings& settings,
             std::vector<uint8_t>& color) {
  const CacheState* const caches[] = {&cache};
  std::vector<uint8_t>* const colors[] = {&color};
  recolor(drawn, caches, settings, colors);
}

}  // namespace vt::reference
