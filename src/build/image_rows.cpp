#include "build/image_rows.h"

#include <algorithm>

#include "common/error.h"

namespace vt {
namespace {

// Texels as the file stores them: no premultiplication by alpha on reading.
const OIIO::ImageSpec kKeepAlphaAsStored = [] {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return config;
}();

// Converts one texel of `from` channels to `to` channels (see image_rows.h).
void convertTexel(const uint8_t* in, uint32_t from, uint8_t* out, uint32_t to) {
  const bool inColor = from >= 3;
  const bool inAlpha = from == 2 || from >= 4;
  const uint8_t alpha = inAlpha ? in[inColor ? 3 : 1] : 255;
  if (to >= 3) {
    for (uint32_t c = 0; c < 3; ++c) out[c] = inColor ? in[c] : in[0];
    if (to == 4) out[3] = alpha;
  } else {
    // Rec. 709 luminance in integer arithmetic (weights sum to 65536), rounded.
    out[0] =
        inColor
            ? static_cast<uint8_t>((13933u * in[0] + 46871u * in[1] + 4732u * in[2] + 32768u) >> 16)
            : in[0];
    if (to == 2) out[1] = alpha;
  }
}

}  // namespace

ImageRows::ImageRows(const Layout& layout) : layout_(layout) {
  for (const Placement& image : layout.images) byTop_.push_back(&image);
  std::stable_sort(byTop_.begin(), byTop_.end(),
                   [](const Placement* a, const Placement* b) { return a->y < b->y; });
}

void ImageRows::row(uint64_t y, RowRing& rows) {
  const uint32_t channels = layout_.description.channels;
  uint8_t* out = rows.append(y);

  // Close images that ended above this row, open those that start on it.
  std::erase_if(open_, [y](const OpenImage& image) {
    return image.placement->y + image.placement->height <= y;
  });
  while (nextToOpen_ < byTop_.size() && byTop_[nextToOpen_]->y <= y) {
    const Placement* placement = byTop_[nextToOpen_++];
    if (placement->y + placement->height <= y) continue;
    auto input = OIIO::ImageInput::open(placement->file.string(), &kKeepAlphaAsStored);
    if (!input) throw InputError(placement->file, "cannot read image: " + OIIO::geterror());
    open_.push_back({placement, std::move(input),
                     std::vector<uint8_t>(uint64_t{placement->width} * placement->channels)});
  }

  for (OpenImage& image : open_) {
    const Placement& p = *image.placement;
    const int line = static_cast<int>(y - p.y);
    if (!image.input->read_scanlines(0, 0, line, line + 1, 0, 0, static_cast<int>(p.channels),
                                     OIIO::TypeDesc::UINT8, image.scanline.data()))
      throw InputError(
          p.file, "cannot read scanline " + std::to_string(line) + ": " + image.input->geterror());
    uint8_t* to = out + p.x * channels;
    rows.wrote({p.x, p.x + p.width});
    if (p.channels == channels) {
      std::copy(image.scanline.begin(), image.scanline.end(), to);
      continue;
    }
    for (uint32_t x = 0; x < p.width; ++x)
      convertTexel(image.scanline.data() + uint64_t{x} * p.channels, p.channels,
                   to + uint64_t{x} * channels, channels);
  }
}

uint64_t ImageRows::bufferBytes() const {
  uint64_t bytes = 0;
  for (const OpenImage& image : open_) bytes += image.scanline.size();
  return bytes;
}

}  // namespace vt
