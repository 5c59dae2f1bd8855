#include "format/virtual_texture_reader.h"

#include "format/block_decoding.h"

#include <algorithm>
#include <cmath>

#include "common/checksum.h"
#include "common/error.h"
#include "common/little_endian.h"

namespace vt {
namespace {

std::string describe(PageId page) {
  return "page " + std::to_string(absoluteIndex(page)) + " (level " + std::to_string(page.level) +
         ", x " + std::to_string(page.x) + ", y " + std::to_string(page.y) + ")";
}

}  // namespace

VirtualTextureReader::VirtualTextureReader(const std::filesystem::path& path)
    : file_(PosixFile::openForReading(path)) {
  const uint64_t size = file_.size();
  std::array<std::byte, kHeaderBytes> headerBytes{};
  const size_t headerRead = static_cast<size_t>(std::min<uint64_t>(size, kHeaderBytes));
  file_.readExact(0, std::span(headerBytes).first(headerRead));
  header_ = decodeHeader(std::span(headerBytes).first(headerRead), size, path);
  identity_ = headerChecksum(headerBytes);

  // The tables lie within the file (decodeHeader checked the file's size), so their size is
  // bounded by what is on disk.
  const FileLayout& layout = header_.layout;
  std::vector<std::byte> tables(layout.dataOffset - layout.indexOffset);
  file_.readExact(layout.indexOffset, tables);
  if (checksum64(tables) != header_.tablesChecksum)
    throw InputError(path,
                     "header field tables_checksum: does not match the page index, "
                     "NoiseValue and checksum tables (a table is corrupted)");

  const uint64_t n = header_.storedPageCount;
  const std::byte* p = tables.data();
  if (header_.sparse) {
    index_.resize(n);
    for (uint64_t k = 0; k < n; ++k) index_[k] = loadU64(p + 8 * k);
    if (const auto problem = findIndexProblem(index_, description().totalPages()))
      throw InputError(path, "sparse index: " + *problem);
    p += 8 * n;
  }
  noiseValues_.resize(n);
  for (uint64_t k = 0; k < n; ++k) {
    noiseValues_[k] = loadF32(p + 4 * k);
    if (!std::isfinite(noiseValues_[k]) || noiseValues_[k] < 0.0f)
      throw InputError(path, "NoiseValue table: entry " + std::to_string(k) + " is " +
                                 std::to_string(noiseValues_[k]) + ", not a finite value >= 0");
  }
  p += 4 * n;
  pageChecksums_.resize(n);
  for (uint64_t k = 0; k < n; ++k) pageChecksums_[k] = loadU64(p + 8 * k);
  if (header_.ancestorErrors) readAncestorErrors();
}

// The ancestor errors after the pages (file_header.h): checked against their checksum, then each
// row: values in [0, 2] up to the page's level, zero from it on.
void VirtualTextureReader::readAncestorErrors() {
  const uint64_t n = header_.storedPageCount, row = ancestorErrorsPerPage(description());
  std::vector<std::byte> bytes(4 * n * row);
  file_.readExact(header_.layout.ancestorErrorOffset, bytes);
  if (checksum64(bytes) != header_.ancestorErrorChecksum)
    throw InputError(path(),
                     "header field ancestor_error_checksum: does not match the ancestor errors "
                     "(the table is corrupted)");
  ancestorErrors_.resize(n * row);
  for (uint64_t k = 0; k < n; ++k) {
    const uint32_t level = levelOfAbsoluteIndex(storedPage(k));
    for (uint64_t l = 0; l < row; ++l) {
      const float e = loadF32(bytes.data() + 4 * (k * row + l));
      if (!isValidAncestorError(e, l, level))
        throw InputError(path(), "ancestor errors: " + describe(fromAbsoluteIndex(storedPage(k))) +
                                     " holds " + std::to_string(e) + " for level " +
                                     std::to_string(l) +
                                     (l < level ? ", not a value in [0, 2]"
                                                : ", no level above the page's (must be 0)"));
      ancestorErrors_[k * row + l] = e;
    }
  }
}

std::span<const float> VirtualTextureReader::ancestorErrors(PageId page) const {
  if (!header_.ancestorErrors) return {};
  const uint64_t row = ancestorErrorsPerPage(description());
  return std::span(ancestorErrors_).subspan(requireSlot(page) * row, page.level);
}

std::optional<uint64_t> VirtualTextureReader::storageSlot(PageId page) const {
  if (page.level >= description().levelCount || !isValid(page)) return std::nullopt;
  const uint64_t absolute = absoluteIndex(page);
  if (!header_.sparse) return absolute;
  const auto it = std::lower_bound(index_.begin(), index_.end(), absolute);
  if (it == index_.end() || *it != absolute) return std::nullopt;
  return static_cast<uint64_t>(it - index_.begin());
}

uint64_t VirtualTextureReader::storedPage(uint64_t slot) const {
  return header_.sparse ? index_.at(slot) : slot;
}

std::vector<uint64_t> VirtualTextureReader::storedPagesPerLevel() const {
  std::vector<uint64_t> counts(description().levelCount, 0);
  if (!header_.sparse) {
    for (uint32_t m = 0; m < counts.size(); ++m) counts[m] = pagesInLevel(m);
    return counts;
  }
  for (const uint64_t page : index_) ++counts[levelOfAbsoluteIndex(page)];
  return counts;
}

uint64_t VirtualTextureReader::requireSlot(PageId page) const {
  const auto slot = storageSlot(page);
  if (!slot) throw InputError(path(), describe(page) + " is not stored in this texture");
  return *slot;
}

float VirtualTextureReader::noiseValue(PageId page) const {
  return noiseValues_[requireSlot(page)];
}

void VirtualTextureReader::readPage(PageId page, std::span<std::byte> texels,
                                    BlockDecoding decoding) const {
  const TextureDescription& d = description();
  if (texels.size() != d.pageBytes())
    throw std::invalid_argument("readPage: buffer of " + std::to_string(texels.size()) +
                                " bytes for a page of " + std::to_string(d.pageBytes()));
  if (!isBlockCompressed(d.format)) {
    readStoredPage(page, texels);
    return;
  }
  std::vector<std::byte> blocks(d.storedPageBytes());
  readStoredPage(page, blocks);
  decodeBlocks(d.format, d.storedPageSide(), blocks, texels, decoding);
}

void VirtualTextureReader::readStoredPage(PageId page, std::span<std::byte> bytes) const {
  const uint64_t slot = requireSlot(page);
  const uint64_t storedBytes = description().storedPageBytes();
  if (bytes.size() != storedBytes)
    throw std::invalid_argument("readStoredPage: buffer of " + std::to_string(bytes.size()) +
                                " bytes for a page of " + std::to_string(storedBytes));
  file_.readExact(header_.layout.dataOffset + slot * storedBytes, bytes);
  if (checksum64(bytes) != pageChecksums_[slot])
    throw InputError(path(), describe(page) + ": checksum mismatch (the page data is corrupted)");
}

std::vector<std::byte> VirtualTextureReader::readPage(PageId page, BlockDecoding decoding) const {
  std::vector<std::byte> texels(description().pageBytes());
  readPage(page, texels, decoding);
  return texels;
}

std::vector<std::byte> VirtualTextureReader::readStoredPage(PageId page) const {
  std::vector<std::byte> bytes(description().storedPageBytes());
  readStoredPage(page, bytes);
  return bytes;
}

}  // namespace vt
