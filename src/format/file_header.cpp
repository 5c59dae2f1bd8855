#include "format/file_header.h"

#include <algorithm>
#include <cstring>

#include "common/checksum.h"
#include "common/error.h"
#include "common/little_endian.h"
#include "common/resource_limits.h"

namespace vt {
namespace {

// Byte offsets of the header fields (see file_header.h).
enum Field : size_t {
  kMagic = 0,
  kVersion = 8,
  kHeaderBytesField = 12,
  kPageSize = 16,
  kBorder = 20,
  kLevelCount = 24,
  kChannels = 28,
  kPixelFormat = 32,
  kColorSpace = 36,
  kFlags = 40,
  kReserved0 = 44,
  kStoredPageCount = 48,
  kIndexOffset = 56,
  kNoiseOffset = 64,
  kChecksumOffset = 72,
  kDataOffset = 80,
  kFileBytes = 88,
  kTablesChecksum = 96,
  kAncestorErrorOffset = 104,
  kAncestorErrorChecksum = 112,
  kHeaderChecksum = 120,
};

std::string fieldError(const std::string& field, const std::string& problem) {
  return "header field " + field + ": " + problem;
}

}  // namespace

FileLayout layoutFor(const TextureDescription& description, bool sparse, uint64_t storedPages,
                     bool ancestorErrors) {
  FileLayout layout;
  layout.indexOffset = kHeaderBytes;
  layout.noiseOffset = layout.indexOffset + (sparse ? 8 * storedPages : 0);
  layout.checksumOffset = layout.noiseOffset + 4 * storedPages;
  layout.dataOffset = layout.checksumOffset + 8 * storedPages;
  layout.fileBytes = layout.dataOffset + storedPages * description.storedPageBytes();
  if (ancestorErrors) {
    layout.ancestorErrorOffset = layout.fileBytes;
    layout.fileBytes += 4 * storedPages * ancestorErrorsPerPage(description);
  }
  return layout;
}

uint64_t headerChecksum(std::span<const std::byte, kHeaderBytes> bytes) {
  return checksum64(bytes.first(kHeaderChecksum));
}

std::array<std::byte, kHeaderBytes> encodeHeader(const FileHeader& header) {
  std::array<std::byte, kHeaderBytes> bytes{};
  std::byte* p = bytes.data();
  for (size_t i = 0; i < kFileMagic.size(); ++i) p[kMagic + i] = std::byte(kFileMagic[i]);
  const TextureDescription& d = header.description;
  storeU32(p + kVersion, fileVersionOf(d.format, header.ancestorErrors));
  storeU32(p + kHeaderBytesField, kHeaderBytes);
  storeU32(p + kPageSize, d.pageSize);
  storeU32(p + kBorder, d.border);
  storeU32(p + kLevelCount, d.levelCount);
  storeU32(p + kChannels, d.channels);
  storeU32(p + kPixelFormat, static_cast<uint32_t>(d.format));
  storeU32(p + kColorSpace, static_cast<uint32_t>(d.colorSpace));
  storeU32(p + kFlags, (header.sparse ? kFlagSparse : 0) |
                           (header.ancestorErrors ? kFlagAncestorErrors : 0));
  storeU64(p + kStoredPageCount, header.storedPageCount);
  storeU64(p + kIndexOffset, header.layout.indexOffset);
  storeU64(p + kNoiseOffset, header.layout.noiseOffset);
  storeU64(p + kChecksumOffset, header.layout.checksumOffset);
  storeU64(p + kDataOffset, header.layout.dataOffset);
  storeU64(p + kFileBytes, header.layout.fileBytes);
  storeU64(p + kTablesChecksum, header.tablesChecksum);
  storeU64(p + kAncestorErrorOffset, header.layout.ancestorErrorOffset);
  storeU64(p + kAncestorErrorChecksum, header.ancestorErrorChecksum);
  storeU64(p + kHeaderChecksum, headerChecksum(bytes));
  return bytes;
}

namespace {

[[noreturn]] void failField(const std::filesystem::path& path, const std::string& field,
                            const std::string& problem) {
  throw InputError(path, fieldError(field, problem));
}

// The size, the magic number and the header's own version and size: returns the version.
uint32_t readPreamble(std::span<const std::byte> bytes, const std::filesystem::path& path) {
  if (bytes.size() < kHeaderBytes)
    throw InputError(path, "truncated: " + std::to_string(bytes.size()) +
                               " bytes, a virtual-texture header needs " +
                               std::to_string(kHeaderBytes));
  const std::byte* p = bytes.data();
  if (std::memcmp(p + kMagic, kFileMagic.data(), kFileMagic.size()) != 0)
    throw InputError(path, "not a virtual-texture file (wrong magic number)");
  const uint32_t version = loadU32(p + kVersion);
  if (version < 1 || version > kFileVersion)
    failField(path, "version",
              std::to_string(version) + " is not supported (this build reads versions 1 to " +
                  std::to_string(kFileVersion) + ")");
  if (const uint32_t size = loadU32(p + kHeaderBytesField); size != kHeaderBytes)
    failField(path, "header_bytes",
              std::to_string(size) + " is not " + std::to_string(kHeaderBytes));
  return version;
}

// The texture's description, valid and of a format the file's version may hold.
TextureDescription readDescription(const std::byte* p, uint32_t version,
                                   const std::filesystem::path& path) {
  TextureDescription d;
  d.pageSize = loadU32(p + kPageSize);
  d.border = loadU32(p + kBorder);
  d.levelCount = loadU32(p + kLevelCount);
  d.channels = loadU32(p + kChannels);
  d.format = static_cast<PixelFormat>(loadU32(p + kPixelFormat));
  d.colorSpace = static_cast<ColorSpace>(loadU32(p + kColorSpace));
  if (const auto problem = findProblem(d)) failField(path, problem->field, problem->problem);
  if (version < fileVersionOf(d.format))
    failField(path, "pixel_format",
              toString(d.format) + " needs version " + std::to_string(fileVersionOf(d.format)) +
                  ", the file is version " + std::to_string(version));
  return d;
}

// The flags and the stored page count, which a dense texture fixes and a sparse one bounds.
void readPageCount(const std::byte* p, uint32_t version, FileHeader& header,
                   const std::filesystem::path& path) {
  const TextureDescription& d = header.description;
  const uint32_t flags = loadU32(p + kFlags);
  if ((flags & ~(kFlagSparse | kFlagAncestorErrors)) != 0)
    failField(path, "flags", "unknown bits set in " + std::to_string(flags));
  header.sparse = (flags & kFlagSparse) != 0;
  header.ancestorErrors = (flags & kFlagAncestorErrors) != 0;
  if (header.ancestorErrors && version < 3)
    failField(path, "flags", "bit 1 (ancestor errors) needs version 3, the file is version " +
                                 std::to_string(version));

  header.storedPageCount = loadU64(p + kStoredPageCount);
  const uint64_t total = d.totalPages();
  if (header.sparse && (header.storedPageCount < 1 || header.storedPageCount > total))
    failField(path, "stored_page_count",
              std::to_string(header.storedPageCount) + " is outside [1, " + std::to_string(total) +
                  "] for a sparse texture of " + std::to_string(d.levelCount) + " levels");
  if (!header.sparse && header.storedPageCount != total)
    failField(path, "stored_page_count",
              std::to_string(header.storedPageCount) + " is not the " + std::to_string(total) +
                  " pages of a dense texture of " + std::to_string(d.levelCount) + " levels");

  // Before any size is derived from the count: the reader's tables hold 20 bytes per page.
  if (header.storedPageCount > kMaxStoredPages)
    throw limitError(path, "header field stored_page_count", header.storedPageCount,
                     kMaxStoredPages, " pages");
}

// Every section must lie exactly where the description and the page count put it, and the file
// must end where the last one does.
void readLayout(const std::byte* p, FileHeader& header, uint64_t fileBytes,
                const std::filesystem::path& path) {
  const TextureDescription& d = header.description;
  const FileLayout expected =
      layoutFor(d, header.sparse, header.storedPageCount, header.ancestorErrors);
  FileLayout& layout = header.layout;
  layout.indexOffset = loadU64(p + kIndexOffset);
  layout.noiseOffset = loadU64(p + kNoiseOffset);
  layout.checksumOffset = loadU64(p + kChecksumOffset);
  layout.dataOffset = loadU64(p + kDataOffset);
  layout.ancestorErrorOffset = loadU64(p + kAncestorErrorOffset);
  layout.fileBytes = loadU64(p + kFileBytes);
  const std::string pages = std::to_string(header.storedPageCount);
  if (layout.indexOffset != expected.indexOffset)
    failField(
        path, "index_offset",
        std::to_string(layout.indexOffset) + " is not " + std::to_string(expected.indexOffset));
  if (layout.noiseOffset != expected.noiseOffset)
    failField(path, "noise_offset",
              "the sparse index between index_offset and noise_offset is " +
                  std::to_string(static_cast<int64_t>(layout.noiseOffset - layout.indexOffset)) +
                  " bytes, " + pages + " stored pages need " +
                  std::to_string(expected.noiseOffset - expected.indexOffset));
  if (layout.checksumOffset != expected.checksumOffset)
    failField(path, "checksum_offset",
              std::to_string(layout.checksumOffset) + " is not " +
                  std::to_string(expected.checksumOffset) + " (after " + pages + " NoiseValues)");
  if (layout.dataOffset != expected.dataOffset)
    failField(path, "data_offset",
              std::to_string(layout.dataOffset) + " is not " + std::to_string(expected.dataOffset) +
                  " (after " + pages + " page checksums)");
  if (layout.ancestorErrorOffset != expected.ancestorErrorOffset)
    failField(path, "ancestor_error_offset",
              std::to_string(layout.ancestorErrorOffset) + " is not " +
                  std::to_string(expected.ancestorErrorOffset) +
                  (header.ancestorErrors ? " (after " + pages + " pages)"
                                         : " (the flags name no ancestor errors)"));
  if (layout.fileBytes != expected.fileBytes)
    failField(path, "file_bytes",
              std::to_string(layout.fileBytes) + " is not the " +
                  std::to_string(expected.fileBytes) + " bytes that " + pages + " pages of " +
                  std::to_string(d.storedPageBytes()) + " bytes need" +
                  (header.ancestorErrors ? ", with their ancestor errors" : ""));
  if (fileBytes < layout.fileBytes)
    throw InputError(path, "truncated: the header declares " + std::to_string(layout.fileBytes) +
                               " bytes, the file has " + std::to_string(fileBytes));
  if (fileBytes > layout.fileBytes)
    throw InputError(path, std::to_string(fileBytes - layout.fileBytes) +
                               " unexpected bytes after the last page (the header declares " +
                               std::to_string(layout.fileBytes) + ")");
}

}  // namespace

FileHeader decodeHeader(std::span<const std::byte> bytes, uint64_t fileBytes,
                        const std::filesystem::path& path) {
  const uint32_t version = readPreamble(bytes, path);
  const std::byte* p = bytes.data();
  FileHeader header;
  header.description = readDescription(p, version, path);
  readPageCount(p, version, header, path);
  readLayout(p, header, fileBytes, path);

  const auto isZero = [&](size_t offset, size_t size) {
    return std::all_of(p + offset, p + offset + size,
                       [](std::byte b) { return b == std::byte{0}; });
  };
  if (!isZero(kReserved0, 4)) failField(path, "reserved", "reserved bytes are not zero");
  header.tablesChecksum = loadU64(p + kTablesChecksum);
  header.ancestorErrorChecksum = loadU64(p + kAncestorErrorChecksum);
  if (!header.ancestorErrors && header.ancestorErrorChecksum != 0)
    failField(path, "ancestor_error_checksum", "is not zero, and the flags name no ancestor errors");
  if (loadU64(p + kHeaderChecksum) != headerChecksum(bytes.first<kHeaderBytes>()))
    failField(path, "header_checksum", "does not match the header (the header is corrupted)");
  return header;
}

std::optional<std::string> findIndexProblem(std::span<const uint64_t> storedPages,
                                            uint64_t totalPages) {
  if (storedPages.empty() || storedPages.front() != 0)
    return "the root page (p_abs 0) is not stored";
  for (size_t k = 1; k < storedPages.size(); ++k) {
    const uint64_t page = storedPages[k];
    if (page <= storedPages[k - 1])
      return "entry " + std::to_string(k) + " (p_abs " + std::to_string(page) +
             ") does not rise above the entry before it";
    if (page >= totalPages)
      return "entry " + std::to_string(k) + " (p_abs " + std::to_string(page) +
             ") is beyond the texture's " + std::to_string(totalPages) + " pages";
    const uint64_t parentPage = parentIndex(page);
    if (!std::binary_search(storedPages.begin(), storedPages.begin() + k, parentPage))
      return "entry " + std::to_string(k) + " (p_abs " + std::to_string(page) +
             ") is stored without its parent (p_abs " + std::to_string(parentPage) + ")";
  }
  return std::nullopt;
}

}  // namespace vt
