#include "format/block_decoding.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace vt {
namespace {

using Palette = std::array<BlockTexel, 4>;  // colour palette entries (alpha unused)

uint32_t loadLittle(const std::byte* p, int bytes) {
  uint32_t value = 0;
  for (int k = bytes - 1; k >= 0; --k) value = (value << 8) | static_cast<uint32_t>(p[k]);
  return value;
}

int widen5(int v) { return (v << 3) | (v >> 2); }
int widen6(int v) { return (v << 2) | (v >> 4); }

// The k-th of n steps from a to b (0 < k < n) under one rule, for the rules that work on 8-bit
// end points alone.
int step(PaletteRule rule, int a, int b, int k, int n) {
  const int sum = (n - k) * a + k * b;
  switch (rule) {
    case PaletteRule::kNearest:
      return (2 * sum + n) / (2 * n);
    case PaletteRule::kTruncated:
      return sum / n;
    case PaletteRule::kFixedPointLerp:
    case PaletteRule::kFixedPointLerpFlooredHalf:
      if (2 * k == n) return (a + b + (rule == PaletteRule::kFixedPointLerp ? 1 : 0)) >> 1;
      return a + (((b - a) * (k * 255 / n)) >> 8);  // >> of a negative: floor (C++20)
    case PaletteRule::kAmd:
      if (2 * k == n) return (a + b + 1) >> 1;
      return k == 1 ? (43 * a + 21 * b + 32) >> 6 : (21 * a + 43 * b + 32) >> 6;
    case PaletteRule::kNvidia:
    case PaletteRule::kWeights:
      break;  // needs the 5-bit end points (nvidiaChannel) or the weights (alphaPalette)
  }
  return sum / n;
}

// The k-th of n steps from a to b as the specification's fraction rounded up (rounded down, it is
// the truncated member).
int stepRoundedUp(int a, int b, int k, int n) { return ((n - k) * a + k * b + n - 1) / n; }

// NVIDIA's BC3 alpha palette, measured (block_decoding.h): the k-th of n steps lies between the
// end points weighted by these sixty-fourths of b, rounded down and rounded up.
constexpr int kNvidiaAlphaSevenths[6] = {9, 18, 28, 36, 46, 55};
constexpr int kNvidiaAlphaFifths[4] = {12, 24, 40, 52};

std::array<int, 2> nvidiaAlphaStepRange(int a, int b, int k, int n) {
  const int w = n == 7 ? kNvidiaAlphaSevenths[k - 1] : kNvidiaAlphaFifths[k - 1];
  const int sum = (64 - w) * a + w * b;
  return {sum / 64, (sum + 63) / 64};
}

// NVIDIA's published colour interpolation: red and blue from their 5-bit end points, green from
// its 8-bit ones (k = 1: c2, k = 2: c3, or the midpoint when `half`).
int nvidiaChannel(int channel, int raw0, int raw1, int k, bool half) {
  if (channel != 1) {
    if (half) return ((raw0 + raw1) * 33) / 8;
    return k == 1 ? ((2 * raw0 + raw1) * 22) / 8 : ((raw0 + 2 * raw1) * 22) / 8;
  }
  const int a = widen6(raw0), b = widen6(raw1), d = b - a;
  if (half) return (256 * a + d / 4 + 128 + d * 128) / 256;
  return k == 1 ? (256 * a + d / 4 + 128 + d * 80) / 256 : (256 * b - d / 4 + 128 - d * 80) / 256;
}

struct ColourBlock {
  int raw[2][3];  // 5-, 6- and 5-bit end points
  int wide[2][3];
  bool four;
};

ColourBlock readColour(const std::byte* block, bool fourColoursAlways) {
  const uint32_t c0 = loadLittle(block, 2), c1 = loadLittle(block + 2, 2);
  ColourBlock b{};
  const uint32_t c[2] = {c0, c1};
  for (int e = 0; e < 2; ++e) {
    b.raw[e][0] = static_cast<int>((c[e] >> 11) & 31);
    b.raw[e][1] = static_cast<int>((c[e] >> 5) & 63);
    b.raw[e][2] = static_cast<int>(c[e] & 31);
    b.wide[e][0] = widen5(b.raw[e][0]);
    b.wide[e][1] = widen6(b.raw[e][1]);
    b.wide[e][2] = widen5(b.raw[e][2]);
  }
  b.four = fourColoursAlways || c0 > c1;
  return b;
}

Palette colourPalette(const ColourBlock& b, PaletteRule rule) {
  Palette p{};
  for (int c = 0; c < 3; ++c) {
    const int a = b.wide[0][c], z = b.wide[1][c];
    int v2, v3;
    if (rule == PaletteRule::kNvidia) {
      v2 = nvidiaChannel(c, b.raw[0][c], b.raw[1][c], 1, !b.four);
      v3 = b.four ? nvidiaChannel(c, b.raw[0][c], b.raw[1][c], 2, false) : 0;
    } else if (b.four) {
      v2 = step(rule, a, z, 1, 3);
      v3 = step(rule, a, z, 2, 3);
    } else {
      v2 = step(rule, a, z, 1, 2);
      v3 = 0;
    }
    const auto c8 = static_cast<size_t>(c);
    p[0][c8] = static_cast<uint8_t>(a);
    p[1][c8] = static_cast<uint8_t>(z);
    p[2][c8] = static_cast<uint8_t>(std::clamp(v2, 0, 255));
    p[3][c8] = static_cast<uint8_t>(std::clamp(v3, 0, 255));
  }
  return p;
}

std::array<uint8_t, 8> alphaPalette(const std::byte* block, PaletteRule rule,
                                    const AlphaWeights& weights = {}) {
  const int a0 = std::to_integer<int>(block[0]), a1 = std::to_integer<int>(block[1]);
  std::array<uint8_t, 8> p{static_cast<uint8_t>(a0), static_cast<uint8_t>(a1)};
  const int n = a0 > a1 ? 7 : 5;
  constexpr int kOne = 1 << kPaletteWeightBits;
  for (int k = 1; k < n; ++k) {
    int v;
    if (rule == PaletteRule::kWeights) {
      const int w = weights[alphaWeightSlot(a0, a1, k)];
      v = (a0 * (kOne - w) + a1 * w + kOne / 2) >> kPaletteWeightBits;
    } else {
      v = step(rule, a0, a1, k, n);
    }
    p[static_cast<size_t>(k + 1)] = static_cast<uint8_t>(v);
  }
  if (n == 5) {
    p[6] = 0;
    p[7] = 255;
  }
  return p;
}

uint32_t colourIndex(const std::byte* colourBlock, uint32_t texel) {
  return (loadLittle(colourBlock + 4, 4) >> (2 * texel)) & 3;
}

const std::byte* colourPart(PixelFormat format, const std::byte* block) {
  return format == PixelFormat::kBc1 ? block : block + 8;
}

}  // namespace

uint32_t alphaIndex(const std::byte* block, uint32_t texel) {
  const uint64_t indices = loadLittle(block + 2, 3) | (uint64_t{loadLittle(block + 5, 3)} << 24);
  return static_cast<uint32_t>((indices >> (3 * texel)) & 7);
}

std::array<BlockTexel, 16> decodeBlock(PixelFormat format, const std::byte* block,
                                       BlockDecoding decoding) {
  const bool bc1 = format == PixelFormat::kBc1;
  const std::byte* colour = colourPart(format, block);
  const Palette palette = colourPalette(readColour(colour, !bc1), decoding.colour);
  std::array<uint8_t, 8> alpha{};
  if (!bc1) alpha = alphaPalette(block, decoding.alpha, decoding.alphaWeights);
  std::array<BlockTexel, 16> texels;
  for (uint32_t t = 0; t < 16; ++t) {
    texels[t] = palette[colourIndex(colour, t)];
    texels[t][3] = bc1 ? 255 : alpha[alphaIndex(block, t)];
  }
  return texels;
}

std::array<BlockTexel, 2> decodeTexelRange(PixelFormat format, const std::byte* block,
                                           uint32_t index) {
  // Every member, the truncated one being the fraction rounded down; then the fraction rounded up.
  const std::byte* colour = colourPart(format, block);
  const ColourBlock b = readColour(colour, format != PixelFormat::kBc1);
  const uint32_t ci = colourIndex(colour, index);
  BlockTexel lo = colourPalette(b, PaletteRule::kNearest)[ci], hi = lo;
  for (const auto& [rule, name] : kPaletteRuleNames) {
    if (!isColourRule(rule)) continue;
    const BlockTexel v = colourPalette(b, rule)[ci];
    for (size_t c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], v[c]);
      hi[c] = std::max(hi[c], v[c]);
    }
  }
  if (ci == 2 || (ci == 3 && b.four))  // a third, or the three-colour midpoint
    for (size_t c = 0; c < 3; ++c) {
      const int up = b.four ? stepRoundedUp(b.wide[0][c], b.wide[1][c], static_cast<int>(ci) - 1, 3)
                            : stepRoundedUp(b.wide[0][c], b.wide[1][c], 1, 2);
      hi[c] = std::max<uint8_t>(hi[c], static_cast<uint8_t>(up));
    }
  if (format == PixelFormat::kBc1) {
    lo[3] = hi[3] = 255;
    return {lo, hi};
  }
  const uint32_t ai = alphaIndex(block, index);
  const int a0 = std::to_integer<int>(block[0]), a1 = std::to_integer<int>(block[1]);
  const int n = a0 > a1 ? 7 : 5, k = static_cast<int>(ai) - 1;
  int aLo = alphaPalette(block, PaletteRule::kNearest)[ai], aHi = aLo;
  // The weights member has no weights of its own: the measured steps below bound the one known.
  for (const auto& [rule, name] : kPaletteRuleNames)
    if (isAlphaRule(rule) && rule != PaletteRule::kWeights) {
      const int v = alphaPalette(block, rule)[ai];
      aLo = std::min(aLo, v);
      aHi = std::max(aHi, v);
    }
  if (k >= 1 && k < n) {
    aHi = std::max(aHi, stepRoundedUp(a0, a1, k, n));
    const std::array<int, 2> nvidia = nvidiaAlphaStepRange(a0, a1, k, n);
    aLo = std::min(aLo, nvidia[0]);
    aHi = std::max(aHi, nvidia[1]);
  }
  lo[3] = static_cast<uint8_t>(aLo);
  hi[3] = static_cast<uint8_t>(aHi);
  return {lo, hi};
}

void decodeBlocks(PixelFormat format, uint32_t width, uint32_t height,
                  std::span<const std::byte> blocks, std::span<std::byte> rgba,
                  BlockDecoding decoding) {
  const std::string size = std::to_string(width) + " x " + std::to_string(height) + " texels";
  if (!isBlockCompressed(format) || width % 4 != 0 || height % 4 != 0)
    throw std::invalid_argument("decodeBlocks: not a block format, or " + size);
  const size_t perRow = width / 4, rows = height / 4, bytes = blockBytes(format);
  const size_t rowStride = size_t{width} * 4;
  if (rgba.size() != rowStride * height || blocks.size() != perRow * rows * bytes)
    throw std::invalid_argument("decodeBlocks: buffers of " + std::to_string(rgba.size()) +
                                " and " + std::to_string(blocks.size()) + " bytes for " + size);
  for (size_t by = 0; by < rows; ++by)
    for (size_t bx = 0; bx < perRow; ++bx) {
      const std::array<BlockTexel, 16> decoded =
          decodeBlock(format, blocks.data() + (by * perRow + bx) * bytes, decoding);
      std::byte* texels = rgba.data() + by * 4 * rowStride + bx * 16;
      for (uint32_t t = 0; t < 16; ++t)
        for (size_t k = 0; k < 4; ++k)
          texels[(t / 4) * rowStride + (t % 4) * 4 + k] = static_cast<std::byte>(decoded[t][k]);
    }
}

void decodeBlocks(PixelFormat format, uint32_t side, std::span<const std::byte> blocks,
                  std::span<std::byte> rgba, BlockDecoding decoding) {
  decodeBlocks(format, side, side, blocks, rgba, decoding);
}

}  // namespace vt
