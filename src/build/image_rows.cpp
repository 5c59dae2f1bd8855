#include "build/image_rows.h"

#include <algorithm>
#include <map>

#include "common/error.h"
#include "common/input_file.h"

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

void convertTexels(const uint8_t* in, uint32_t from, uint8_t* out, uint32_t to, uint64_t count) {
  if (from == to) {
    std::copy_n(in, count * from, out);
    return;
  }
  for (uint64_t t = 0; t < count; ++t) convertTexel(in + t * from, from, out + t * to, to);
}

std::unique_ptr<OIIO::ImageInput> openImage(const Placement& p) {
  requireRegularFile(p.file, "image");
  auto input = OIIO::ImageInput::open(p.file.string(), &kKeepAlphaAsStored);
  if (!input) throw InputError(p.file, "cannot read image: " + OIIO::geterror());
  return input;
}

// Reads scanlines [y0, y1) of the placement's image as 8-bit values of its own channels.
void readScanlines(OIIO::ImageInput& input, const Placement& p, uint32_t y0, uint32_t y1,
                   uint8_t* out) {
  if (!input.read_scanlines(0, 0, static_cast<int>(y0), static_cast<int>(y1), 0, 0,
                            static_cast<int>(p.channels), OIIO::TypeDesc::UINT8, out))
    throw InputError(
        p.file, "cannot read scanline" +
                    (y1 == y0 + 1 ? " " + std::to_string(y0)
                                  : "s " + std::to_string(y0) + " to " + std::to_string(y1 - 1)) +
                    ": " + input.geterror());
}

// The placement's whole image in `channels` channels, read forwards in bands of scanlines.
std::vector<uint8_t> readWhole(const Placement& p, uint32_t channels) {
  const auto input = openImage(p);
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width != static_cast<int>(p.imageWidth) ||
      spec.height != static_cast<int>(p.imageHeight) ||
      spec.nchannels != static_cast<int>(p.channels))
    throw InputError(p.file, "the image changed since the layout was read");
  const uint64_t w = p.imageWidth;
  std::vector<uint8_t> texels(w * p.imageHeight * channels);
  std::vector<uint8_t> band(w * ImageRows::kBandRows * p.channels);
  for (uint32_t y0 = 0; y0 < p.imageHeight; y0 += ImageRows::kBandRows) {
    const uint32_t y1 = std::min(y0 + ImageRows::kBandRows, p.imageHeight);
    readScanlines(*input, p, y0, y1, band.data());
    convertTexels(band.data(), p.channels, texels.data() + y0 * w * channels, channels,
                  (y1 - y0) * w);
  }
  return texels;
}

// a mod m, the non-negative remainder.
uint64_t floorMod(int64_t a, uint64_t m) {
  const int64_t r = a % static_cast<int64_t>(m);
  return static_cast<uint64_t>(r < 0 ? r + static_cast<int64_t>(m) : r);
}

// Row j of a region placement (layout.h): image row (sourceY + j) mod h, from column
// sourceX mod w on, wrapping to column 0 as often as the placed width asks.
void copyRegionRow(const Placement& p, const std::vector<uint8_t>& image, uint64_t j,
                   uint32_t channels, uint8_t* out) {
  const uint64_t w = p.imageWidth;
  const uint8_t* line =
      image.data() + floorMod(p.sourceY + static_cast<int64_t>(j), p.imageHeight) * w * channels;
  uint64_t column = floorMod(p.sourceX, w);
  for (uint64_t i = 0; i < p.width; column = 0) {
    const uint64_t run = std::min(w - column, p.width - i);
    std::copy_n(line + column * channels, run * channels, out + i * channels);
    i += run;
  }
}

}  // namespace

ImageRows::ImageRows(const Layout& layout) : layout_(layout) {
  std::map<std::filesystem::path, size_t> wholeOfFile;
  for (const Placement& image : layout.images) {
    if (!image.region) {
      byTop_.push_back({&image, kStreamed});
      continue;
    }
    const auto [known, added] = wholeOfFile.emplace(image.file.lexically_normal(), wholes_.size());
    if (added) wholes_.push_back({&image, 0, {}});
    WholeImage& whole = wholes_[known->second];
    whole.endRow = std::max(whole.endRow, image.y + image.height);
    byTop_.push_back({&image, known->second});
  }
  std::stable_sort(byTop_.begin(), byTop_.end(), [](const Pending& a, const Pending& b) {
    return a.placement->y < b.placement->y;
  });
}

void ImageRows::open(const Pending& pending) {
  const Placement& p = *pending.placement;
  if (pending.whole == kStreamed) {
    open_.push_back(
        {&p, openImage(p), std::vector<uint8_t>(uint64_t{p.imageWidth} * p.channels), kStreamed});
    return;
  }
  WholeImage& whole = wholes_[pending.whole];
  if (whole.texels.empty()) {
    whole.texels = readWhole(*whole.first, layout_.description.channels);
    held_.push_back(pending.whole);
  }
  open_.push_back({&p, nullptr, {}, pending.whole});
}

void ImageRows::row(uint64_t y, RowRing& rows) {
  const uint32_t channels = layout_.description.channels;
  rows.append(y);

  // Close placements that ended above this row, release the images no later row needs, open the
  // placements that start on this row.
  std::erase_if(open_, [y](const OpenImage& image) {
    return image.placement->y + image.placement->height <= y;
  });
  std::erase_if(held_, [&](size_t w) {
    if (wholes_[w].endRow > y) return false;
    std::vector<uint8_t>().swap(wholes_[w].texels);
    return true;
  });
  while (nextToOpen_ < byTop_.size() && byTop_[nextToOpen_].placement->y <= y) {
    const Pending& pending = byTop_[nextToOpen_++];
    if (pending.placement->y + pending.placement->height > y) open(pending);
  }

  for (OpenImage& image : open_) {
    const Placement& p = *image.placement;
    placed_.resize(uint64_t{p.width} * channels);
    if (image.whole != kStreamed) {
      copyRegionRow(p, wholes_[image.whole].texels, y - p.y, channels, placed_.data());
    } else {
      const auto line = static_cast<uint32_t>(y - p.y);
      readScanlines(*image.input, p, line, line + 1, image.scanline.data());
      convertTexels(image.scanline.data(), p.channels, placed_.data(), channels, p.width);
    }
    rows.declare({p.x, p.x + p.width});
    rows.write(p.x, placed_.data(), p.width);
  }
}

uint64_t ImageRows::bufferBytes() const {
  uint64_t bytes = 0;
  for (const OpenImage& image : open_) bytes += image.scanline.size();
  for (const size_t w : held_) bytes += wholes_[w].texels.size();
  return bytes;
}

}  // namespace vt
