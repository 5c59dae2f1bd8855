#pragma once
// The on-disk layout of a virtual-texture file, versions 1 to 3 (docs/design.md section 2). All
// integers are little-endian. Sections follow each other without gaps, in this order:
//
//   offset            size                      what
//   0                 128                       header (below)
//   index_offset      8 * n, sparse only        absolute indices p_abs of the stored pages, rising
//   noise_offset      4 * n                     NoiseValue of each stored page (float32)
//   checksum_offset   8 * n                     XXH3-64 of each stored page's bytes
//   data_offset       n * page bytes            the stored pages, in rising p_abs: (P + 2B)^2 * c
//                                               for unorm8, ((P + 2B) / 4)^2 blocks of 8 (bc1)
//                                               or 16 (bc3) bytes
//   ancestor_error_offset  4 * n * L, version 3  the ancestor errors (build/ancestor_error.h) of
//                                               each stored page: L float32, entry l the error
//                                               through its ancestor on level l, zero from the
//                                               page's own level on
//   file_bytes                                  end of file
//
// n is stored_page_count: every page of every level for a dense texture, the pages listed in the
// index for a sparse one (the root and, with every page, its parent). Table entry k belongs to the
// k-th stored page, so a page is one contiguous read at data_offset + k * page_bytes, and
// the NoiseValues are read without touching page data.
//
// Header (128 bytes):
//    0  magic            89 'V' 'T' 'X' 0D 0A 1A 0A   (the PNG trick: detects text-mode damage)
//    8  u32 version      1 for unorm8 (every file before block compression), 2 for bc1 and bc3,
//                        3 for a file with ancestor errors (any pixel format)
//   12  u32 header_bytes 128
//   16  u32 page_size    P        20  u32 border        B
//   24  u32 level_count  L + 1    28  u32 channels      1..4
//   32  u32 pixel_format 1 unorm8, 2 bc1, 3 bc3 (channels 4, P + 2B a multiple of 4)
//   36  u32 color_space   0 linear, 1 sRGB
//   40  u32 flags        bit 0: sparse, bit 1: ancestor errors (version 3)
//   44  u32 reserved, zero
//   48  u64 stored_page_count     56  u64 index_offset  64  u64 noise_offset
//   72  u64 checksum_offset       80  u64 data_offset   88  u64 file_bytes
//   96  u64 tables_checksum       XXH3-64 of the bytes [index_offset, data_offset)
//  104  u64 ancestor_error_offset   data_offset + n * page bytes with bit 1, else zero
//  112  u64 ancestor_error_checksum XXH3-64 of the ancestor errors with bit 1, else zero
//  120  u64 header_checksum       XXH3-64 of the bytes [0, 120)

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "format/texture_description.h"

namespace vt {

// The newest version this build reads. A file is written in the oldest version that holds its
// pixel format and its sections, so unorm8 files without ancestor errors stay version 1, byte for
// byte as before.
inline constexpr uint32_t kFileVersion = 3;
constexpr uint32_t fileVersionOf(PixelFormat format, bool ancestorErrors = false) {
  return ancestorErrors ? 3 : isBlockCompressed(format) ? 2 : 1;
}
inline constexpr uint32_t kHeaderBytes = 128;
inline constexpr std::array<uint8_t, 8> kFileMagic = {0x89, 'V', 'T', 'X', 0x0D, 0x0A, 0x1A, 0x0A};
inline constexpr uint32_t kFlagSparse = 1u << 0;
inline constexpr uint32_t kFlagAncestorErrors = 1u << 1;

// Where each section lies, all derived from the description and the number of stored pages.
struct FileLayout {
  uint64_t indexOffset = kHeaderBytes;
  uint64_t noiseOffset = 0;
  uint64_t checksumOffset = 0;
  uint64_t dataOffset = 0;
  uint64_t ancestorErrorOffset = 0;  // 0: no ancestor errors
  uint64_t fileBytes = 0;
};

// Floats of ancestor errors per stored page: one per level but the finest (L = level_count - 1).
constexpr uint64_t ancestorErrorsPerPage(const TextureDescription& d) { return d.levelCount - 1; }
// Entry `level` of a page on `pageLevel`: finite in [0, 2] through a coarser level, 0 from its own
// level on.
inline bool isValidAncestorError(float error, uint64_t level, uint32_t pageLevel) {
  return level < pageLevel ? std::isfinite(error) && error >= 0.0f && error <= 2.0f
                           : error == 0.0f;
}

// The layout of a file with `storedPages` pages. The limits of TextureDescription keep every sum
// far below 2^63: n < 4^16 / 3 and page_bytes < 2^33.
FileLayout layoutFor(const TextureDescription& description, bool sparse, uint64_t storedPages,
                     bool ancestorErrors = false);

struct FileHeader {
  TextureDescription description;
  bool sparse = false;
  uint64_t storedPageCount = 0;
  bool ancestorErrors = false;
  FileLayout layout;
  uint64_t tablesChecksum = 0;
  uint64_t ancestorErrorChecksum = 0;  // with ancestorErrors
};

std::array<std::byte, kHeaderBytes> encodeHeader(const FileHeader& header);

// Decodes and validates the header of `path`, whose size is `fileBytes`: each field against the
// format's limits (stored_page_count at most kMaxStoredPages, common/resource_limits.h), the
// sections against each other and against the file's size, then the header checksum. Throws
// InputError naming the file and the first bad field.
FileHeader decodeHeader(std::span<const std::byte> bytes, uint64_t fileBytes,
                        const std::filesystem::path& path);

// XXH3-64 of the header's first 120 bytes; also the texture's identity (it covers every table,
// and the page checksums cover the pages).
uint64_t headerChecksum(std::span<const std::byte, kHeaderBytes> bytes);

// The first problem of a sparse page index: it must rise strictly, stay below `totalPages`, hold
// the root, and hold the parent of every page it holds (so ancestor fallback always ends on a
// stored page).
std::optional<std::string> findIndexProblem(std::span<const uint64_t> storedPages,
                                            uint64_t totalPages);

}  // namespace vt
