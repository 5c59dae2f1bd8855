#pragma once
// Where the oracle's shader reads texels: a cache state (DESIGN section 4) reduced to what the
// fragment logic fetches. ResidentTexture is the state "every page resident": each lookup names
// the page itself, or on a sparse texture its nearest stored ancestor, and texels come straight
// from the virtual-texture file, each page decoded once.

#include <cstdint>
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

  const TextureDescription& description() const { return reader_.description(); }

  // The page that serves (px, py) of `level`: itself or its nearest stored ancestor.
  PageId residentPage(PageId page) const;

  // The stored texels of a page (borders included), decoded once and kept. Thread-safe.
  const std::vector<std::byte>& texels(PageId page) const;

 private:
  const VirtualTextureReader& reader_;
  mutable std::shared_mutex mutex_;
  mutable std::unordered_map<uint64_t, std::unique_ptr<std::vector<std::byte>>> pages_;
};

}  // namespace vt::reference
