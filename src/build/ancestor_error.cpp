#include "build/ancestor_error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "build/noise_value.h"
#include "common/structural_similarity.h"
#include "format/block_decoding.h"

namespace vt {
namespace {

// Bilinear taps along one axis: for each of q's P texels the ancestor's two stored texel indices
// and the weight of the second.
struct Taps {
  std::vector<uint32_t> first, second;
  std::vector<float> weight;
};

// `offset` is q's position within the ancestor along the axis, in q's pages (x mod 2^d).
Taps tapsOf(const TextureDescription& d, uint64_t offset, uint32_t distance) {
  const int64_t side = d.storedPageSide();
  const double scale = std::ldexp(1.0, -static_cast<int>(distance));
  Taps taps;
  for (uint32_t i = 0; i < d.pageSize; ++i) {
    const double u = (static_cast<double>(offset * d.pageSize) + i + 0.5) * scale - 0.5;
    const double below = std::floor(u);
    const auto x0 = static_cast<int64_t>(below) + d.border;
    taps.first.push_back(static_cast<uint32_t>(std::clamp<int64_t>(x0, 0, side - 1)));
    taps.second.push_back(static_cast<uint32_t>(std::clamp<int64_t>(x0 + 1, 0, side - 1)));
    taps.weight.push_back(static_cast<float>(u - below));
  }
  return taps;
}

// A worker's pages of one level, in Z order so that neighbours share their ancestors, which it
// keeps (one per level) while they serve.
struct AncestorCache {
  std::vector<std::optional<PageId>> page;
  std::vector<std::vector<float>> luminance;
};

uint64_t mortonOf(PageId p) {
  uint64_t code = 0;
  for (uint32_t bit = 0; bit < p.level; ++bit)
    code |= (uint64_t{(p.x >> bit) & 1u} << (2 * bit)) | (uint64_t{(p.y >> bit) & 1u} << (2 * bit + 1));
  return code;
}

}  // namespace

std::vector<float> pageLuminance(const TextureDescription& d, std::span<const std::byte> texels) {
  const size_t count = size_t{d.storedPageSide()} * d.storedPageSide();
  const uint32_t c = isBlockCompressed(d.format) ? 4 : d.channels;
  if (texels.size() != count * c)
    throw std::invalid_argument("pageLuminance: " + std::to_string(texels.size()) +
                                " bytes for a page of " + std::to_string(count * c));
  std::vector<float> y(count);
  for (size_t k = 0; k < count; ++k) y[k] = texelLuminance(texels.data() + k * c, c, 1.0f);
  return y;
}

float ancestorError(const TextureDescription& d, PageId page, std::span<const float> pageY,
                    uint32_t ancestorLevel, std::span<const float> ancestorY) {
  const uint32_t side = d.storedPageSide(), P = d.pageSize, B = d.border;
  if (ancestorLevel >= page.level || pageY.size() != size_t{side} * side ||
      ancestorY.size() != pageY.size())
    throw std::invalid_argument("ancestorError: not an ancestor's level, or pages of other sizes");
  const uint32_t distance = page.level - ancestorLevel;
  const uint64_t mask = (uint64_t{1} << distance) - 1;
  const Taps across = tapsOf(d, page.x & mask, distance), down = tapsOf(d, page.y & mask, distance);
  std::vector<float> interior(size_t{P} * P), resampled(size_t{P} * P);
  for (uint32_t j = 0; j < P; ++j) {
    const float* top = ancestorY.data() + size_t{down.first[j]} * side;
    const float* bottom = ancestorY.data() + size_t{down.second[j]} * side;
    const float fy = down.weight[j];
    for (uint32_t i = 0; i < P; ++i) {
      const float fx = across.weight[i];
      const float upper = top[across.first[i]] * (1 - fx) + top[across.second[i]] * fx;
      const float lower = bottom[across.first[i]] * (1 - fx) + bottom[across.second[i]] * fx;
      resampled[size_t{j} * P + i] = upper * (1 - fy) + lower * fy;
      interior[size_t{j} * P + i] = pageY[size_t{j + B} * side + (i + B)];
    }
  }
  // SSIM is at most 1; rounding may carry a window a hair above it.
  const double error = 1.0 - meanUniformSsim(interior, resampled, P, kAncestorErrorWindow);
  return static_cast<float>(std::clamp(error, 0.0, 2.0));
}

std::vector<float> ancestorErrorTable(
    const TextureDescription& d, std::span<const uint64_t> storedPages,
    const std::function<std::vector<std::byte>(PageId)>& texelsOf) {
  const size_t row = d.levelCount - 1;
  std::vector<float> table(storedPages.size() * row, 0.0f);
  // Each level's stored pages (slot and page) in Z order, in chunks for the workers.
  constexpr size_t kChunk = 64;
  for (uint32_t level = 1; level < d.levelCount; ++level) {
    std::vector<std::pair<uint64_t, size_t>> pages;  // Morton code, slot
    for (size_t slot = 0; slot < storedPages.size(); ++slot) {
      const PageId page = fromAbsoluteIndex(storedPages[slot]);
      if (page.level == level) pages.emplace_back(mortonOf(page), slot);
    }
    std::sort(pages.begin(), pages.end());
    tbb::parallel_for(size_t{0}, (pages.size() + kChunk - 1) / kChunk, [&](size_t chunk) {
      AncestorCache cache{std::vector<std::optional<PageId>>(level),
                          std::vector<std::vector<float>>(level)};
      const size_t end = std::min(pages.size(), (chunk + 1) * kChunk);
      for (size_t k = chunk * kChunk; k < end; ++k) {
        const size_t slot = pages[k].second;
        const PageId page = fromAbsoluteIndex(storedPages[slot]);
        const std::vector<float> own = pageLuminance(d, texelsOf(page));
        for (uint32_t l = 0; l < level; ++l) {
          const PageId up = ancestorAt(page, l);
          if (cache.page[l] != up) {
            cache.luminance[l] = pageLuminance(d, texelsOf(up));
            cache.page[l] = up;
          }
          table[slot * row + l] = ancestorError(d, page, own, l, cache.luminance[l]);
        }
      }
    });
  }
  return table;
}

std::vector<float> ancestorErrorsOfWrittenPages(const VirtualTextureWriter& writer) {
  const TextureDescription& d = writer.description();
  return ancestorErrorTable(d, writer.storedPages(), [&](PageId page) {
    std::vector<std::byte> bytes = writer.readWrittenPage(page);
    if (!isBlockCompressed(d.format)) return bytes;
    std::vector<std::byte> texels(d.pageBytes());
    decodeBlocks(d.format, d.storedPageSide(), bytes, texels);
    return texels;
  });
}

}  // namespace vt
