#include "common/image_file.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/input_file.h"
#include "common/posix_file.h"

namespace vt {

void writeImage8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const std::byte> texels,
                 PngCompression compression) {
  if (texels.size() != uint64_t{width} * height * channels)
    throw std::invalid_argument("writeImage8: texel count does not match the size");
  // The temporary file carries the destination's extension, from which OpenImageIO picks the
  // format; OpenImageIO rewrites it in place and commit() flushes and renames it.
  TemporaryFile output(path);
  const std::string staging = output.file().path().string();
  auto writer = OIIO::ImageOutput::create(staging);
  if (!writer)
    throw InputError(path, "no image writer for the extension '" + path.extension().string() + "'");
  OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height),
                       static_cast<int>(channels), OIIO::TypeDesc::UINT8);
  // The texels are stored as given: alpha is not taken as premultiplied.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (compression == PngCompression::kFast) {
    constexpr int kNoRowFilter = 0x08;  // libpng's PNG_FILTER_NONE
    spec.attribute("png:compressionLevel", 1);
    spec.attribute("png:filter", kNoRowFilter);
  }
  const bool ok = writer->open(staging, spec) &&
                  writer->write_image(OIIO::TypeDesc::UINT8, texels.data()) && writer->close();
  if (!ok) throw InputError(path, "cannot write image: " + writer->geterror());
  output.commit();
}

Image8 readImage8(const std::filesystem::path& path, int maxSide) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  requireRegularFile(path, "image");
  auto input = OIIO::ImageInput::open(path.string(), &config);
  if (!input) throw InputError(path, "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.format != OIIO::TypeDesc::UINT8)
    throw InputError(path,
                     "image has " + std::string(spec.format.c_str()) + " channels, not 8-bit ones");
  if (spec.width < 1 || spec.height < 1 || spec.width > maxSide || spec.height > maxSide ||
      spec.nchannels < 1 || spec.nchannels > 4)
    throw InputError(path, "image is " + std::to_string(spec.width) + " x " +
                               std::to_string(spec.height) + " with " +
                               std::to_string(spec.nchannels) + " channels; at most " +
                               std::to_string(maxSide) + " pixels per side and 4 channels");
  Image8 image{spec.width, spec.height, spec.nchannels, {}};
  image.texels.resize(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) *
                      static_cast<size_t>(spec.nchannels));
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, image.texels.data()))
    throw InputError(path, "cannot read image: " + input->geterror());
  return image;
}

std::optional<ImageHeader> readImageHeader(const std::filesystem::path& path, std::string* error) {
  try {
    requireRegularFile(path, "image");
  } catch (const InputError& e) {
    if (error) *error = e.what();
    return std::nullopt;
  }
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) {
    const std::string reason = OIIO::geterror();  // read, so it does not linger for the next call
    if (error) *error = reason;
    return std::nullopt;
  }
  const OIIO::ImageSpec& spec = input->spec();
  return ImageHeader{spec.width, spec.height, spec.nchannels};
}

std::optional<ImageHeader> readDecodableImageHeader(const std::filesystem::path& path,
                                                    std::string* error) {
  const std::optional<ImageHeader> header = readImageHeader(path, error);
  if (!header || header->width <= 0 || header->height <= 0 || header->channels <= 0)
    return header;
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) {
    if (error) *error = OIIO::geterror();
    return std::nullopt;
  }
  const OIIO::ImageSpec& spec = input->spec();
  // One row (of tiles) at a time: memory for a row, never for the size the header claims.
  const int rows = spec.tile_height > 0 ? spec.tile_height : 1;
  std::vector<unsigned char> buffer(static_cast<size_t>(spec.width) * static_cast<size_t>(rows) *
                                    static_cast<size_t>(spec.nchannels));
  for (int y = 0; y < spec.height; y += rows) {
    const int end = std::min(spec.height, y + rows);
    const bool ok =
        spec.tile_width > 0
            ? input->read_tiles(0, 0, 0, spec.width, y, end, 0, 1, 0, spec.nchannels,
                                OIIO::TypeDesc::UINT8, buffer.data())
            : input->read_scanline(y, 0, OIIO::TypeDesc::UINT8, buffer.data());
    if (!ok) {
      const std::string reason = input->geterror();
      if (error)
        *error = "its header claims " + std::to_string(spec.width) + " x " +
                 std::to_string(spec.height) + " pixels, but row " + std::to_string(y) +
                 " does not decode" + (reason.empty() ? "" : ": " + reason);
      return std::nullopt;
    }
  }
  return header;
}

}  // namespace vt
