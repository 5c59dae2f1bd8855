#pragma once
// Writing 8-bit images through OpenImageIO (format from the extension: .png, .tif, .exr, ...),
// into a temporary file renamed at the end, so a failed write leaves no partial image.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

namespace vt {

// Rows of `width` texels of `channels` bytes each, top row first.
void writeImage8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const std::byte> texels);

}  // namespace vt
