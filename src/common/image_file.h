#pragma once
// Writing 8-bit images through OpenImageIO (format from the extension: .png, .tif, .exr, ...),
// into a temporary file renamed at the end, so a failed write leaves no partial image; and
// reading an image's header.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace vt {

// How a PNG is compressed (other formats ignore it): kSmall with zlib's default level and
// libpng's adaptive row filters, for images kept; kFast with level 1 and no row filter, for the
// images a check writes frame after frame (vt crosscheck's comparison images), where compressing
// at the default level took a fifth of a gl45 crosscheck (docs/benchmarks.md).
enum class PngCompression { kSmall, kFast };

// Rows of `width` texels of `channels` bytes each, top row first.
void writeImage8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const std::byte> texels,
                 PngCompression compression = PngCompression::kSmall);

// An 8-bit image as its file stores it, rows top to bottom.
struct Image8 {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> texels;  // width * height * channels
};

// Reads an image whose channels are 8 bits each, alpha as stored (never premultiplied). Throws
// InputError naming the file when it cannot be read, is not 8 bits per channel, or is larger than
// `maxSide` pixels per side (checked before its pixels are allocated).
Image8 readImage8(const std::filesystem::path& path, int maxSide);

// The size and channels an image file's header states (nothing is decoded).
struct ImageHeader {
  int width = 0, height = 0, channels = 0;
};

// Nothing when OpenImageIO cannot open the file; `error`, if given, then holds its reason.
std::optional<ImageHeader> readImageHeader(const std::filesystem::path& path,
                                           std::string* error = nullptr);

// The same, believed only as far as the pixels decode: every row is decoded, one at a time (a
// header claiming 100000 x 100000 pixels of a file that holds none is nothing, with the row that
// failed in `error`). For images a command sizes its output by.
std::optional<ImageHeader> readDecodableImageHeader(const std::filesystem::path& path,
                                                    std::string* error = nullptr);

}  // namespace vt
