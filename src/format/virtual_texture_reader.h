#pragma once
// Reads a virtual-texture file (file_header.h): validates the header and every table on open,
// then serves pages by random access. Every page is one positional read (pread) followed by its
// checksum check, and the reader holds no mutable state, so any number of threads may read pages
// at once.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include "common/posix_file.h"
#include "format/block_decoding.h"
#include "format/file_header.h"

namespace vt {

class VirtualTextureReader {
 public:
  // Opens and validates `path`; throws InputError naming the file and the first bad field. No
  // allocation depends on a header field before that field was checked against the file's size.
  explicit VirtualTextureReader(const std::filesystem::path& path);

  const std::filesystem::path& path() const { return file_.path(); }
  const TextureDescription& description() const { return header_.description; }
  const FileHeader& header() const { return header_; }
  bool isSparse() const { return header_.sparse; }
  uint64_t storedPageCount() const { return header_.storedPageCount; }
  uint64_t fileBytes() const { return header_.layout.fileBytes; }
  // The texture's identity: the header checksum, which covers the tables and so every page's
  // checksum. Two files with equal identity hold the same pages.
  uint64_t identity() const { return identity_; }

  // Position k of the page among the stored pages, or nothing when the page is not stored.
  std::optional<uint64_t> storageSlot(PageId page) const;
  bool contains(PageId page) const { return storageSlot(page).has_value(); }
  // Absolute index of the k-th stored page.
  uint64_t storedPage(uint64_t slot) const;
  // Stored pages on each level 0..L.
  std::vector<uint64_t> storedPagesPerLevel() const;

  // NoiseValue of a stored page (thesis 3.3.1.2), from the table read on open.
  float noiseValue(PageId page) const;
  std::span<const float> noiseValues() const { return noiseValues_; }
  // Ancestor errors (version 3, `vt build --ancestor-errors`, build/ancestor_error.h): entry l of
  // a stored page's span is its error shown through its ancestor on level l, l < page.level.
  // Empty for every page of a file without them.
  bool hasAncestorErrors() const { return header_.ancestorErrors; }
  std::span<const float> ancestorErrors(PageId page) const;

  // Reads the stored page's (P + 2B)^2 texels into `texels` (exactly description().pageBytes()
  // bytes), verifying its checksum and decoding the block formats to RGBA8 under `decoding`
  // (format/block_decoding.h). Throws InputError for a page that is not stored, a failed
  // read, or a checksum mismatch (naming the page).
  void readPage(PageId page, std::span<std::byte> texels, BlockDecoding decoding = {}) const;
  std::vector<std::byte> readPage(PageId page, BlockDecoding decoding = {}) const;
  // The page's bytes as stored (description().storedPageBytes(): its blocks where the format
  // compresses), checksum verified: what travels from the file.
  void readStoredPage(PageId page, std::span<std::byte> bytes) const;
  std::vector<std::byte> readStoredPage(PageId page) const;

 private:
  uint64_t requireSlot(PageId page) const;
  void readAncestorErrors();

  PosixFile file_;
  FileHeader header_;
  uint64_t identity_ = 0;
  std::vector<uint64_t> index_;  // sparse only: p_abs of the stored pages, rising
  std::vector<float> noiseValues_;
  std::vector<uint64_t> pageChecksums_;
  std::vector<float> ancestorErrors_;  // storedPageCount rows of ancestorErrorsPerPage
};

}  // namespace vt
