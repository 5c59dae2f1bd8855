#pragma once
// The block formats' pages (texture_description.h: bc1, bc3) from RGBA8 texels, with libsquish,
// one 4 x 4 block at a time (its image calls run OpenMP loops of their own; pages are already
// encoded on the build's workers, each page on one). Only the tool chain encodes: the readers
// decode with format/block_decoding.h, which needs no library (vt-capture links no libsquish).
//
// Encoding uses libsquish's range fit: each block's palette spans the extremes of its colours
// along their principal axis, and every texel takes the nearest entry. The library's default,
// the cluster fit (every ordered split of the 16 texels into palette entries, least squares), is
// better, but far too slow for the budget of 3 times an uncompressed build: on the image of
// benchmarks/build_formats.sh (8192^2, gradient and noise, 2 cores) `vt build --format bc1` took
// 95.6 s with it against 2.9 s with the range fit and 1.6 s uncompressed, for a finest level of
// 25.1 dB PSNR against 23.7 dB. BC1 pages are opaque: alpha is set to 255 before encoding, so no
// block takes BC1's punch-through mode.

#include <cstddef>
#include <cstdint>
#include <span>

#include "format/texture_description.h"

namespace vt {

// Encodes a stored page of side x side RGBA8 texels (side a multiple of 4) into blocks of
// `format`: rows of side / 4 blocks, of increasing t. `blocks` holds exactly the page's stored
// bytes (TextureDescription::storedPageBytes).
void encodeBlocks(PixelFormat format, uint32_t side, std::span<const std::byte> rgba,
                  std::span<std::byte> blocks);

}  // namespace vt
