#pragma once
// The finest level of a layout, produced one texel row at a time from its images.
//
// A placement of a whole image (no region fields, layout.h) is streamed: its image is opened when
// the rows reach its top, read one scanline per row, and closed after its last row.
//
// A region placement cannot be streamed: its rows wrap around the image (and JPEG can only be
// read forwards), so its image is read whole once, converted to the texture's channels, and its
// rows are copied from that copy. Every region placement of the same file shares the copy (keyed
// by the file's path), which is read at the top row of the first of them and released after the
// last row of the last of them, kept through rows between them too: each image is read once
// however many faces, spread over the texture, repeat it.
//
// Memory bound (what bufferBytes counts): one scanline (w * image channels bytes) per streamed
// placement crossing the current row, plus w * h * texture channels bytes per distinct image of
// region placements whose span of rows (top of its first placement to bottom of its last)
// contains the current row. While such an image is read, a band of kBandRows of its scanlines is
// held besides, freed before row() returns.
//
// Channel conversion to the texture's channel count: gray spreads to RGB; a missing alpha is
// opaque (255); RGB to gray is Rec. 709 luminance; extra channels are dropped. Values of 16-bit
// and float images are converted to 8 bits by OpenImageIO (scaled, clamped to [0, 1], rounded),
// without a change of transfer function. Both paths convert alike, so a region covering its whole
// image once gives the same texels as the plain placement.

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "build/layout.h"
#include "build/row_ring.h"

namespace vt {

class ImageRows {
 public:
  // Scanlines read at once while an image is read whole.
  static constexpr uint32_t kBandRows = 16;

  explicit ImageRows(const Layout& layout);

  // Appends finest row y to `rows` (rows in increasing order): the images' texels on it, the
  // background elsewhere.
  void row(uint64_t y, RowRing& rows);

  // Scanline buffers and whole images held now (the memory bound above).
  uint64_t bufferBytes() const;

 private:
  // An image read whole for the region placements of its file.
  struct WholeImage {
    const Placement* first;       // the first placement naming it: file, size and channels
    uint64_t endRow;              // one past the last row of its last placement
    std::vector<uint8_t> texels;  // the texture's channels; empty before and after its rows
  };
  struct Pending {
    const Placement* placement;
    size_t whole;  // index in wholes_, kStreamed for a whole-image placement
  };
  // A placement crossing the current row.
  struct OpenImage {
    const Placement* placement;
    std::unique_ptr<OIIO::ImageInput> input;  // streamed: one scanline per row
    std::vector<uint8_t> scanline;
    size_t whole;  // region: rows copied from wholes_[whole]
  };
  static constexpr size_t kStreamed = SIZE_MAX;

  void open(const Pending& pending);

  const Layout& layout_;
  std::vector<Pending> byTop_;  // placements in order of their first row
  size_t nextToOpen_ = 0;
  std::vector<OpenImage> open_;
  std::vector<WholeImage> wholes_;
  std::vector<size_t> held_;  // wholes_ read and not yet released
  std::vector<uint8_t> placed_;  // one placement's texels of the current row, texture channels
};

}  // namespace vt
