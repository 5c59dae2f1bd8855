#pragma once
// The image that stands in for a source texture that cannot be found: a magenta and black checker
// nobody mistakes for content.

#include <cstdint>
#include <filesystem>

#include "scene/textured_scene.h"

namespace vt {

inline constexpr uint32_t kMissingTextureSide = 64;

// Writes the checker (PNG, RGB, kMissingTextureSide^2, squares of 8 texels) as
// `folder`/missing_texture.png unless it exists, and returns its path.
std::filesystem::path writeMissingTexture(const std::filesystem::path& folder);

// Makes `texture` the checker: missing, its file (written into `folder`) and size.
void useMissingTexture(SourceTexture& texture, const std::filesystem::path& folder);

}  // namespace vt
