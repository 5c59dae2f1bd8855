#pragma once
// The finest level of a layout, produced one texel row at a time from its images: each image is
// opened when the rows reach its top, read one scanline per row, and closed after its last row,
// so memory holds one scanline per image that crosses the current row.
//
// Channel conversion to the texture's channel count: gray spreads to RGB; a missing alpha is
// opaque (255); RGB to gray is Rec. 709 luminance; extra channels are dropped. Values of 16-bit
// and float images are converted to 8 bits by OpenImageIO (scaled, clamped to [0, 1], rounded),
// without a change of transfer function.

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "build/layout.h"
#include "build/row_ring.h"

namespace vt {

class ImageRows {
 public:
  explicit ImageRows(const Layout& layout);

  // Appends finest row y to `rows` (rows in increasing order): the images' texels on it, the
  // background elsewhere.
  void row(uint64_t y, RowRing& rows);

  // Scanline buffers held now (for the memory bound).
  uint64_t bufferBytes() const;

 private:
  struct OpenImage {
    const Placement* placement;
    std::unique_ptr<OIIO::ImageInput> input;
    std::vector<uint8_t> scanline;
  };

  const Layout& layout_;
  std::vector<const Placement*> byTop_;  // images in order of their first row
  size_t nextToOpen_ = 0;
  std::vector<OpenImage> open_;
};

}  // namespace vt
