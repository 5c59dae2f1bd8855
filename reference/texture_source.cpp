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

const std::vector<std::byte>& ResidentTexture::kept(
    uint64_t key, const std::function<std::vector<std::byte>()>& load) const {
  {
    const std::shared_lock lock(mutex_);
    const auto it = pages_.find(key);
    if (it != pages_.end()) return *it->second;
  }
  auto loaded = std::make_unique<std::vector<std::byte>>(load());
  const std::unique_lock lock(mutex_);
  auto [it, inserted] = pages_.try_emplace(key, std::move(loaded));
  return *it->second;
}

namespace {

// Keys of pages_: the page, then 6 bits for what its bytes are (the last value: its blocks).
constexpr uint64_t kKinds = 64, kBlocksKind = kKinds - 1;
static_assert(kPaletteRuleNames.size() * kPaletteRuleNames.size() < kBlocksKind);
uint64_t kindOf(BlockDecoding decoding) {
  return static_cast<uint64_t>(decoding.colour) * kPaletteRuleNames.size() +
         static_cast<uint64_t>(decoding.alpha);
}

}  // namespace

const std::vector<std::byte>& ResidentTexture::texels(PageId page, BlockDecoding decoding) const {
  const bool decodes = isBlockCompressed(description_.format);
  const uint64_t key = absoluteIndex(page) * kKinds + (decodes ? kindOf(decoding) : 0);
  return kept(key, [&] { return reader_ ? reader_->readPage(page, decoding) : makePage_(page); });
}

const std::vector<std::byte>& ResidentTexture::blocks(PageId page) const {
  return kept(absoluteIndex(page) * kKinds + kBlocksKind,
              [&] { return reader_ ? reader_->readStoredPage(page) : makePage_(page); });
}

}  // namespace vt::reference
