#include "reference/texture_source.h"

namespace vt::reference {

ResidentTexture::ResidentTexture(const VirtualTextureReader& reader)
    : description_(reader.description()), reader_(&reader) {}

ResidentTexture::ResidentTexture(const TextureDescription& description, PageMaker page)
    : description_(description), makePage_(std::move(page)) {}

PageId ResidentTexture::residentPage(PageId page) const {
  if (!reader_) return page;  // dense
  while (page.level > 0 && !reader_->contains(page)) page = parent(page);
  return page;
}

const std::vector<std::byte>& ResidentTexture::texels(PageId page) const {
  const uint64_t key = absoluteIndex(page);
  {
    const std::shared_lock lock(mutex_);
    const auto it = pages_.find(key);
    if (it != pages_.end()) return *it->second;
  }
  auto loaded = std::make_unique<std::vector<std::byte>>(reader_ ? reader_->readPage(page)
                                                                 : makePage_(page));
  const std::unique_lock lock(mutex_);
  auto [it, inserted] = pages_.try_emplace(key, std::move(loaded));
  return *it->second;
}

}  // namespace vt::reference
