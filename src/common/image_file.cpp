#include "common/image_file.h"

#include <OpenImageIO/imageio.h>

#include <stdexcept>
#include <string>

#include "common/error.h"
#include "common/posix_file.h"

namespace vt {

void writeImage8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const std::byte> texels) {
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
  const bool ok = writer->open(staging, spec) &&
                  writer->write_image(OIIO::TypeDesc::UINT8, texels.data()) && writer->close();
  if (!ok) throw InputError(path, "cannot write image: " + writer->geterror());
  output.commit();
}

std::optional<ImageHeader> readImageHeader(const std::filesystem::path& path, std::string* error) {
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) {
    const std::string reason = OIIO::geterror();  // read, so it does not linger for the next call
    if (error) *error = reason;
    return std::nullopt;
  }
  const OIIO::ImageSpec& spec = input->spec();
  return ImageHeader{spec.width, spec.height, spec.nchannels};
}

}  // namespace vt
