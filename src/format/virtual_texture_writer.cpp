#include "format/virtual_texture_writer.h"


#include <algorithm>
#include <cmath>

#include "common/checksum.h"
#include "common/error.h"
#include "common/little_endian.h"

namespace vt {
namespace {

void requireValid(const std::filesystem::path& destination, const TextureDescription& d) {
  if (const auto problem = findProblem(d))
    throw InputError(destination, "cannot write: " + problem->field + " " + problem->problem);
}

}  // namespace

VirtualTextureWriter::VirtualTextureWriter(const std::filesystem::path& destination,
                                           const TextureDescription& description,
                                           BlockEncoder encoder)
    : VirtualTextureWriter(destination, description, {}, false, encoder) {}

VirtualTextureWriter::VirtualTextureWriter(const std::filesystem::path& destination,
                                           const TextureDescription& description,
                                           std::vector<uint64_t> storedPages, BlockEncoder encoder)
    : VirtualTextureWriter(destination, description, std::move(storedPages), true, encoder) {}

VirtualTextureWriter::VirtualTextureWriter(const std::filesystem::path& destination,
                                           const TextureDescription& description,
                                           std::vector<uint64_t> storedPages, bool sparse,
                                           BlockEncoder encoder)
    : output_((requireValid(destination, description), destination)),
      index_(std::move(storedPages)),
      encoder_(encoder) {
  if (isBlockCompressed(description.format) && !encoder_)
    throw std::invalid_argument("VirtualTextureWriter: pixel format " +
                                toString(description.format) + " needs a block encoder");
  if (sparse) {
    if (const auto problem = findIndexProblem(index_, description.totalPages()))
      throw InputError(destination, "cannot write sparse index: " + *problem);
  }
  header_.description = description;
  header_.sparse = sparse;
  header_.storedPageCount = sparse ? index_.size() : description.totalPages();
  header_.layout = layoutFor(description, sparse, header_.storedPageCount);
  // Size the file first: a size the file system refuses fails here, before the tables below
  // are allocated.
  output_.file().resize(header_.layout.fileBytes);
  noiseValues_.assign(header_.storedPageCount, 0.0f);
  pageChecksums_.assign(header_.storedPageCount, 0);
  written_.assign(header_.storedPageCount, 0);
}

uint64_t VirtualTextureWriter::slotOf(PageId page) const {
  if (page.level >= description().levelCount || !isValid(page))
    throw std::invalid_argument("writePage: page outside the texture");
  const uint64_t absolute = absoluteIndex(page);
  if (!header_.sparse) return absolute;
  const auto it = std::lower_bound(index_.begin(), index_.end(), absolute);
  if (it == index_.end() || *it != absolute)
    throw std::invalid_argument("writePage: page " + std::to_string(absolute) +
                                " is not in the sparse index");
  return static_cast<uint64_t>(it - index_.begin());
}

void VirtualTextureWriter::writePage(PageId page, std::span<const std::byte> texels,
                                     float noiseValue) {
  const uint64_t slot = slotOf(page);
  const uint64_t pageBytes = description().pageBytes();
  if (texels.size() != pageBytes)
    throw std::invalid_argument("writePage: " + std::to_string(texels.size()) +
                                " bytes for a page of " + std::to_string(pageBytes));
  if (!std::isfinite(noiseValue) || noiseValue < 0.0f)
    throw std::invalid_argument("writePage: NoiseValue must be finite and >= 0");
  {
    const std::lock_guard lock(mutex_);
    if (written_[slot])
      throw std::invalid_argument("writePage: page " + std::to_string(absoluteIndex(page)) +
                                  " written twice");
    written_[slot] = 1;
  }
  const TextureDescription& d = description();
  std::vector<std::byte> blocks;
  std::span<const std::byte> stored = texels;
  if (isBlockCompressed(d.format)) {
    blocks.resize(d.storedPageBytes());
    encoder_(d.format, d.storedPageSide(), texels, blocks);
    stored = blocks;
  }
  const uint64_t checksum = checksum64(stored);
  output_.file().writeAll(header_.layout.dataOffset + slot * d.storedPageBytes(), stored);
  const std::lock_guard lock(mutex_);
  noiseValues_[slot] = noiseValue;
  pageChecksums_[slot] = checksum;
}

std::vector<std::byte> VirtualTextureWriter::readWrittenPage(PageId page) const {
  const uint64_t slot = slotOf(page);
  uint64_t checksum = 0;
  {
    const std::lock_guard lock(mutex_);
    if (!written_[slot])
      throw std::invalid_argument("readWrittenPage: page " + std::to_string(absoluteIndex(page)) +
                                  " was not written");
    checksum = pageChecksums_[slot];
  }
  const uint64_t storedBytes = description().storedPageBytes();
  std::vector<std::byte> bytes(storedBytes);
  output_.file().readExact(header_.layout.dataOffset + slot * storedBytes, bytes);
  if (checksum64(bytes) != checksum)
    throw InputError(destination(), "page " + std::to_string(absoluteIndex(page)) +
                                        " reads back other bytes than were written");
  return bytes;
}

std::vector<uint64_t> VirtualTextureWriter::storedPages() const {
  if (header_.sparse) return index_;
  std::vector<uint64_t> all(header_.storedPageCount);
  for (uint64_t k = 0; k < all.size(); ++k) all[k] = k;
  return all;
}

void VirtualTextureWriter::setAncestorErrors(std::vector<float> errors) {
  const uint64_t row = ancestorErrorsPerPage(description());
  if (errors.size() != header_.storedPageCount * row)
    throw std::invalid_argument("setAncestorErrors: " + std::to_string(errors.size()) +
                                " values for " + std::to_string(header_.storedPageCount) +
                                " pages of " + std::to_string(row));
  for (uint64_t k = 0; k < header_.storedPageCount; ++k) {
    const uint32_t level = levelOfAbsoluteIndex(header_.sparse ? index_[k] : k);
    for (uint64_t l = 0; l < row; ++l) {
      const float e = errors[k * row + l];
      if (!isValidAncestorError(e, l, level))
        throw std::invalid_argument("setAncestorErrors: stored page " + std::to_string(k) +
                                    " holds " + std::to_string(e) + " for level " +
                                    std::to_string(l));
    }
  }
  const std::lock_guard lock(mutex_);
  ancestorErrors_ = std::move(errors);
  hasAncestorErrors_ = true;
}

void VirtualTextureWriter::commit() {
  const std::lock_guard lock(mutex_);
  const auto missing = std::find(written_.begin(), written_.end(), uint8_t{0});
  if (missing != written_.end()) {
    const uint64_t slot = static_cast<uint64_t>(missing - written_.begin());
    const uint64_t count = static_cast<uint64_t>(std::count(missing, written_.end(), uint8_t{0}));
    throw InputError(destination(), "cannot commit: " + std::to_string(count) +
                                        " pages were never written, the first is page " +
                                        std::to_string(header_.sparse ? index_[slot] : slot));
  }

  const FileLayout& layout = header_.layout;
  const uint64_t n = header_.storedPageCount;
  std::vector<std::byte> tables(layout.dataOffset - layout.indexOffset);
  std::byte* p = tables.data();
  if (header_.sparse) {
    for (uint64_t k = 0; k < n; ++k) storeU64(p + 8 * k, index_[k]);
    p += 8 * n;
  }
  for (uint64_t k = 0; k < n; ++k) storeF32(p + 4 * k, noiseValues_[k]);
  p += 4 * n;
  for (uint64_t k = 0; k < n; ++k) storeU64(p + 8 * k, pageChecksums_[k]);
  header_.tablesChecksum = checksum64(tables);
  output_.file().writeAll(layout.indexOffset, tables);

  if (hasAncestorErrors_) {
    header_.ancestorErrors = true;
    header_.layout = layoutFor(description(), header_.sparse, n, true);
    std::vector<std::byte> errors(4 * ancestorErrors_.size());
    for (size_t k = 0; k < ancestorErrors_.size(); ++k)
      storeF32(errors.data() + 4 * k, ancestorErrors_[k]);
    header_.ancestorErrorChecksum = checksum64(errors);
    output_.file().resize(header_.layout.fileBytes);
    output_.file().writeAll(header_.layout.ancestorErrorOffset, errors);
  }
  output_.file().writeAll(0, encodeHeader(header_));
  output_.commit();
}

}  // namespace vt
