#pragma once
// The block formats' pages (texture_description.h: bc1, bc3) decoded to RGBA8 texels. Written
// here, without a library, so that every program that reads textures (vt-capture too) decodes
// the same way.
//
// What the S3TC specification (EXT_texture_compression_s3tc) fixes:
//   - colour end points c0, c1 (RGB565) widened to 8 bits by replicating their top bits;
//   - BC1 with c0 > c1, and every BC3 colour block: c2 = (2 c0 + c1) / 3, c3 = (c0 + 2 c1) / 3
//     per channel; BC1 with c0 <= c1: c2 = (c0 + c1) / 2 and c3 black (BC1 pages are opaque:
//     alpha 255 throughout);
//   - BC3 alpha a0, a1: with a0 > a1, a_i = ((8 - i) a0 + (i - 1) a1) / 7 for i = 2..7; else
//     a_i = ((6 - i) a0 + (i - 1) a1) / 5 for i = 2..5, a6 = 0, a7 = 255;
//   - 2-bit (colour) and 3-bit (alpha) indices per texel, row by row, the first texel in the
//     lowest bits.
// What it leaves open is how these fractions become 8-bit values: that is a family of choices of
// the oracle's arithmetic (render/arithmetic.h), one rule for the colour palette and one for the
// alpha palette. The members, with where each comes from:
//   nearest           each fraction rounded to nearest, halves up: the specification's values as
//                     closely as 8 bits hold them (the exact point)
//   truncated         each fraction rounded down: Mesa's util decoder (u_format_s3tc), which
//                     softpipe samples; measured bit for bit by `vt calibrate`'s decoding probes
//                     (src/calibrate/decoding_fit.h; tests/gl/calibration_test.cpp)
//   fixed_point_lerp  a + floor((b - a) * floor(k * 255 / n) / 256) for the k-th of n steps, and
//                     the BC1 midpoint as (a + b + 1) >> 1: llvmpipe's (gallivm) decoder, measured
//                     bit for bit on every palette entry by the same probes
//   fixed_point_lerp_floored_half
//                     colour only: as fixed_point_lerp, but the BC1 midpoint floored, (a + b) >> 1:
//                     llvmpipe without SSE (GALLIUM_OVERRIDE_CPU_CAPS=nosse), measured the same way
//                     (its alpha palettes have no midpoint: they are fixed_point_lerp's)
//   amd               colour only: (43 a + 21 b + 32) >> 6 and the midpoint (a + b + 1) >> 1 on
//                     8-bit end points, as published for AMD GPUs by the rgbcx encoder
//   weights           alpha only: the k-th of n steps as (a (4096 - w) + b w + 2048) >> 12 with one
//                     measured integer weight w per step (BlockDecoding::alphaWeights: six for
//                     sevenths, then four for fifths), fitted by `vt calibrate` on a GPU's dense
//                     alpha probe (data/gpus/nvidia-h100/bc3-alpha.u8: w = 578, 1156, 1784, 2312,
//                     2940, 3518 and 770, 1540, 2556, 3326 reproduce every end-point pair there)
//   nvidia            colour only: red and blue interpolated on the 5-bit end points,
//                     ((2 a + b) * 22) / 8 and midpoint ((a + b) * 33) / 8, green from the 8-bit
//                     end points as (256 a + d / 4 + 128 + 80 d) / 256 with d = b - a (midpoint:
//                     128 d), as published for NVIDIA GPUs since G80 (NVIDIA Texture Tools, rgbcx)
// The published hardware members are not measured here; `vt calibrate` measures whichever the
// implementation under test computes (src/calibrate/decoding_fit.h).
//
// NVIDIA's BC3 alpha palette is no member (nothing published reproduces it, and no closed form
// found here does bit for bit), but it is measured: texelFetch of every alpha end-point pair at
// every index on an NVIDIA H100 (driver 580.159.04; data/gpus/nvidia-h100/bc3-alpha.u8.gz) gave
// values that all lie between the end points weighted by 9, 18, 28, 36, 46, 55 sixty-fourths of
// a1 (a0 > a1) or by 12, 24, 40, 52 sixty-fourths (a0 <= a1), rounded down and rounded up; in the
// six-value mode that is up to 6.6 / 255 from the specification's fifths. decodeTexelRange takes
// it in, as it takes in every member.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "common/enum_names.h"
#include "format/texture_description.h"

namespace vt {

enum class PaletteRule {
  kNearest,
  kTruncated,
  kFixedPointLerp,
  kFixedPointLerpFlooredHalf,
  kAmd,
  kNvidia,
  kWeights
};
inline constexpr EnumNames<PaletteRule, 7> kPaletteRuleNames = {
    {{PaletteRule::kNearest, "nearest"},
     {PaletteRule::kTruncated, "truncated"},
     {PaletteRule::kFixedPointLerp, "fixed_point_lerp"},
     {PaletteRule::kFixedPointLerpFlooredHalf, "fixed_point_lerp_floored_half"},
     {PaletteRule::kAmd, "amd"},
     {PaletteRule::kNvidia, "nvidia"},
     {PaletteRule::kWeights, "weights"}}};

// The members a BC3 alpha palette may use (the published hardware rules describe colour only;
// without a midpoint, fixed_point_lerp_floored_half is fixed_point_lerp).
constexpr bool isAlphaRule(PaletteRule rule) {
  return rule == PaletteRule::kNearest || rule == PaletteRule::kTruncated ||
         rule == PaletteRule::kFixedPointLerp || rule == PaletteRule::kWeights;
}
// The members a colour palette may use.
constexpr bool isColourRule(PaletteRule rule) { return rule != PaletteRule::kWeights; }

// The weights member's fraction bits: w / 2^12 of the far end point.
inline constexpr int kPaletteWeightBits = 12;
// Its weights: steps 1 to 6 of sevenths (a0 > a1), then steps 1 to 4 of fifths (a0 <= a1).
using AlphaWeights = std::array<uint16_t, 10>;
// The weight step k (1-based) of end points a0, a1 uses.
constexpr size_t alphaWeightSlot(int a0, int a1, int k) {
  return static_cast<size_t>(a0 > a1 ? k - 1 : 5 + k);
}

struct BlockDecoding {
  PaletteRule colour = PaletteRule::kNearest;
  PaletteRule alpha = PaletteRule::kNearest;
  AlphaWeights alphaWeights{};  // alpha == kWeights only
  bool operator==(const BlockDecoding&) const = default;
};

using BlockTexel = std::array<uint8_t, 4>;

// Bytes of one block of `format` (8 for bc1, 16 for bc3).
constexpr size_t blockBytes(PixelFormat format) { return format == PixelFormat::kBc1 ? 8 : 16; }

// Decodes a texture of width x height texels (multiples of 4) from its blocks (rows of width / 4
// blocks of increasing t) into RGBA8 rows.
void decodeBlocks(PixelFormat format, uint32_t width, uint32_t height,
                  std::span<const std::byte> blocks, std::span<std::byte> rgba,
                  BlockDecoding decoding = {});
// The same for a stored page of side x side texels (TextureDescription::storedPageBytes blocks).
void decodeBlocks(PixelFormat format, uint32_t side, std::span<const std::byte> blocks,
                  std::span<std::byte> rgba, BlockDecoding decoding = {});

// The 3-bit alpha index of texel `texel` (row * 4 + column) of a BC3 block.
uint32_t alphaIndex(const std::byte* block, uint32_t texel);

// The 16 texels of one block, row by row.
std::array<BlockTexel, 16> decodeBlock(PixelFormat format, const std::byte* block,
                                       BlockDecoding decoding);

// What any conforming implementation may return for texel `index` (row * 4 + column) of one block:
// per channel the least and the greatest value of every member above, of NVIDIA's measured alpha
// steps rounded either way, and of the specification's fraction rounded either way (GL 4.5
// section 2.3.5.2 lets a conversion to fixed point round either way). End points, c3 black and
// the alpha constants are exact in every member.
std::array<BlockTexel, 2> decodeTexelRange(PixelFormat format, const std::byte* block,
                                           uint32_t index);

}  // namespace vt
