#include "vt/oracle/texture.h"

#include "reference/api/api_internal.h"

namespace vt::oracle {

Error::Error(const std::string& message) : std::runtime_error(message) {}
Error::~Error() = default;

Texture Texture::open(const std::filesystem::path& path) {
  return translatingErrors([&] { return Texture(std::make_unique<Impl>(path)); });
}

Texture::Texture(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Texture::Texture(Texture&&) noexcept = default;
Texture& Texture::operator=(Texture&&) noexcept = default;
Texture::~Texture() = default;

const std::filesystem::path& Texture::path() const { return impl_->reader.path(); }
uint32_t Texture::pageSize() const { return impl_->reader.description().pageSize; }
uint32_t Texture::border() const { return impl_->reader.description().border; }
uint32_t Texture::levelCount() const { return impl_->reader.description().levelCount; }
uint32_t Texture::channels() const { return impl_->reader.description().channels; }
uint64_t Texture::side() const { return impl_->reader.description().sideTexels(); }
bool Texture::isSparse() const { return impl_->reader.isSparse(); }
uint64_t Texture::identity() const { return impl_->reader.identity(); }

bool Texture::contains(uint32_t level, uint32_t px, uint32_t py) const {
  const PageId page{px, py, level};
  return level < levelCount() && isValid(page) && impl_->reader.contains(page);
}

}  // namespace vt::oracle
