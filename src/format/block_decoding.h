#pragma once
// The block formats' pages (texture_description.h: bc1, bc3) decoded to RGBA8 texels, as the
// readers serve them (format/virtual_texture_reader.h). Written here, without a library, so that
// every program that reads textures (vt-capture too) decodes the same way.
//
// The decoding is the S3TC specification's (EXT_texture_compression_s3tc) with its exact thirds
// rounded to nearest:
//   - colour end points c0, c1 (RGB565) widened to 8 bits by replicating their top bits;
//   - BC1 with c0 > c1, and every BC3 colour block: c2 = round((2 c0 + c1) / 3),
//     c3 = round((c0 + 2 c1) / 3) per channel; BC1 with c0 <= c1: c2 = round((c0 + c1) / 2) and
//     c3 black (BC1 pages are opaque: alpha 255 throughout);
//   - BC3 alpha a0, a1: with a0 > a1, a_i = round(((8 - i) a0 + (i - 1) a1) / 7) for i = 2..7;
//     else a_i = round(((6 - i) a0 + (i - 1) a1) / 5) for i = 2..5, a6 = 0, a7 = 255;
//   - 2-bit (colour) and 3-bit (alpha) indices per texel, row by row, the first texel in the
//     lowest bits; halves round up.

#include <cstddef>
#include <cstdint>
#include <span>

#include "format/texture_description.h"

namespace vt {

// Decodes a stored page of side x side texels (side a multiple of 4) from its blocks (rows of
// side / 4 blocks of increasing t, TextureDescription::storedPageBytes of them) into RGBA8.
void decodeBlocks(PixelFormat format, uint32_t side, std::span<const std::byte> blocks,
                  std::span<std::byte> rgba);

}  // namespace vt
