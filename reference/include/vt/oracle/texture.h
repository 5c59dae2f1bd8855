#pragma once
// A virtual-texture file (.vt, written by `vt build`), opened for the oracle: its pages of
// (P + 2B)^2 texels on levels 0..L (level 0 is one page, level m has 2^m x 2^m) and its
// identity, the checksum that names its content in captures.

#include <cstdint>
#include <filesystem>
#include <memory>

#include "vt/oracle/export.h"

namespace vt::oracle {

class VT_ORACLE_API Texture {
 public:
  // Opens and validates the file; throws Error naming the file and the first bad field.
  static Texture open(const std::filesystem::path& path);

  Texture(Texture&&) noexcept;
  Texture& operator=(Texture&&) noexcept;
  ~Texture();

  const std::filesystem::path& path() const;
  uint32_t pageSize() const;    // P, texels per page side without borders
  uint32_t border() const;      // B
  uint32_t levelCount() const;  // L + 1
  uint32_t channels() const;    // 1..4, unorm8
  uint64_t side() const;        // texels per side of the finest level, P * 2^L
  bool isSparse() const;        // stores only some pages of the finer levels
  // XXH3-64 of the header, which covers the file's tables and so every page's checksum: two
  // files with the same identity hold the same pages.
  uint64_t identity() const;
  // Whether the page (px, py) of `level` is stored in the file.
  bool contains(uint32_t level, uint32_t px, uint32_t py) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  explicit Texture(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vt::oracle
