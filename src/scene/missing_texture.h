#pragma once
// The image that stands in for a source texture that cannot be found: a magenta and black checker
// nobody mistakes for content.

#include <cstdint>
#include <filesystem>

namespace vt {

inline constexpr uint32_t kMissingTextureSide = 64;

// Writes the checker (PNG, RGB, kMissingTextureSide^2, squares of 8 texels) as
// `folder`/missing_texture.png unless it exists, and returns its path.
std::filesystem::path writeMissingTexture(const std::filesystem::path& folder);

}  // namespace vt
