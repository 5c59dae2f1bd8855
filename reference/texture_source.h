#pragma once
// Where the oracle's shader reads texels: a cache state (docs/design.md section 4) reduced to what
// the fragment logic fetches. ResidentTexture is the state "every page resident": each lookup names
// the page itself, or on a sparse texture its nearest stored ancestor, and texels come straight
// from the virtual-texture file, each page decoded once; or, for a dense texture made in memory
// (the calibration's probe texture), from a function that makes a page's texels.

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <vector>

#include "format/virtual_texture_reader.h"

namespace vt::reference {

class ResidentTexture {
 public:
  explicit ResidentTexture(const VirtualTextureReader& reader);
  // Every page of `description` stored, its texels (borders included) made by `page`.
  using PageMaker = std::function<std::vector<std::byte>(PageId)>;
  ResidentTexture(const TextureDescription& description, PageMaker page);

  const TextureDescription& description() const { return description_; }

  // The page that serves (px, py) of `level`: itself or its nearest stored ancestor.
  PageId residentPage(PageId page) const;

  // The stored texels of a page (borders included), decoded once per block decoding and kept.
  // Thread-safe.
  const std::vector<std::byte>& texels(PageId page, BlockDecoding decoding = {}) const;
  // Block formats: the page's blocks as stored, read once and kept. Thread-safe.
  const std::vector<std::byte>& blocks(PageId page) const;

 private:
  const std::vector<std::byte>& kept(uint64_t key,
                                     const std::function<std::vector<std::byte>()>& load) const;

  const TextureDescription description_;
  const VirtualTextureReader* reader_ = nullptr;  // or, for a texture made in memory, makePage_
  PageMaker makePage_;
  mutable std::shared_mutex mutex_;
  // By page and what the bytes are: texels under one decoding, or the stored blocks.
  mutable std::unordered_map<uint64_t, std::unique_ptr<std::vector<std::byte>>> pages_;
};

}  // namespace vt::reference
