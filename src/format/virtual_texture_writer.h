#pragma once
// Writes a virtual-texture file (file_header.h) into a temporary file next to the destination and
// renames it on commit(), so the destination holds either its previous content or a complete,
// valid file. The set of stored pages is fixed up front, so every page has a fixed place: pages
// may be written in any order, from any number of threads, and the bytes of the file do not
// depend on that order.

#include <cstddef>
#include <concepts>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <span>
#include <vector>

#include "common/posix_file.h"
#include "format/file_header.h"

namespace vt {

// Encodes a stored page of side x side RGBA8 texels into blocks of a block format: the tool
// chain's encodeBlocks (build/block_encoding.h; the format part itself only decodes). A class,
// so that a brace list meant as a sparse index ({0}) never becomes a null encoder.
class BlockEncoder {
 public:
  using Function = void (*)(PixelFormat format, uint32_t side, std::span<const std::byte> rgba,
                            std::span<std::byte> blocks);
  BlockEncoder() = default;
  // A template only so that nothing but a function converts: not 0, not a brace list.
  template <class F>
    requires std::same_as<F, Function>
  explicit BlockEncoder(F encode) : encode_(encode) {}
  explicit operator bool() const { return encode_ != nullptr; }
  void operator()(PixelFormat format, uint32_t side, std::span<const std::byte> rgba,
                  std::span<std::byte> blocks) const {
    encode_(format, side, rgba, blocks);
  }

 private:
  Function encode_ = nullptr;
};

class VirtualTextureWriter {
 public:
  // A dense texture: every page of every level is stored. A block format needs `encoder`.
  VirtualTextureWriter(const std::filesystem::path& destination,
                       const TextureDescription& description, BlockEncoder encoder = {});
  // A sparse texture storing only `storedPages` (absolute indices, rising, holding the root and
  // the parent of every page they hold).
  VirtualTextureWriter(const std::filesystem::path& destination,
                       const TextureDescription& description, std::vector<uint64_t> storedPages,
                       BlockEncoder encoder = {});

  const TextureDescription& description() const { return header_.description; }
  const std::filesystem::path& destination() const { return output_.destination(); }

  // Stores one page: (P + 2B)^2 texels, rows of increasing t (RGBA8 for the block formats, which
  // it encodes on the calling thread with the encoder), and its NoiseValue (>= 0).
  // Each stored page is written exactly once. Thread-safe.
  void writePage(PageId page, std::span<const std::byte> texels, float noiseValue);

  // A written page's bytes as stored (its blocks for the block formats), read back from the file
  // and checked against the checksum taken when it was written. Thread-safe.
  std::vector<std::byte> readWrittenPage(PageId page) const;

  // The ancestor errors (build/ancestor_error.h) to store after the pages: storedPages() rows of
  // ancestorErrorsPerPage(description()) values, each row's values in [0, 2] below the page's
  // level and 0 from it on. The file becomes version 3.
  void setAncestorErrors(std::vector<float> errors);
  // The stored pages' absolute indices, rising.
  std::vector<uint64_t> storedPages() const;

  // Writes the tables and the header, flushes, and renames the file to its destination. Throws if
  // a page was never written; the destination is then untouched.
  void commit();

 private:
  VirtualTextureWriter(const std::filesystem::path& destination,
                       const TextureDescription& description, std::vector<uint64_t> storedPages,
                       bool sparse, BlockEncoder encoder);
  uint64_t slotOf(PageId page) const;

  TemporaryFile output_;
  FileHeader header_;
  std::vector<uint64_t> index_;
  BlockEncoder encoder_;
  mutable std::mutex mutex_;  // guards the tables below
  std::vector<float> noiseValues_;
  std::vector<uint64_t> pageChecksums_;
  std::vector<uint8_t> written_;
  std::vector<float> ancestorErrors_;
  bool hasAncestorErrors_ = false;
};

}  // namespace vt
