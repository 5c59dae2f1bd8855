#pragma once
// What `vt build` compiles (thesis 3.3.1, "vtmtc"): images placed at texel positions of the finest
// level of one square texture, with the page size, border, filter and colour handling.
//
// Layout file (JSON; image paths relative to the layout file's folder):
//   {
//     "page_size": 128,            // P, a power of two (default 128)
//     "border": 4,                 // B < P (default 4)
//     "side": 16384,               // finest level side, P * 2^L (default: the smallest that
//                                  // holds every image)
//     "channels": 3,               // 1..4 (default: the most channels of any image)
//     "color_space": "srgb",       // "srgb" (default) or "linear": how texels are encoded
//     "filter": "box",             // "box" (default) or "tent": the mip filter
//     "format": "rgba8",           // "rgba8" (default), "bc1" or "bc3": the stored pages
//     "background": [0, 0, 0, 0],  // texels no image covers (default transparent black)
//     "images": [ { "file": "wall.tga", "x": 0, "y": 0 }, ... ]
//   }
// x grows with s, y with t (rows of the texture, top row of each image first). Placements must
// not overlap and must lie inside the texture.
//
// A placement may name a region of its image, repeated (thesis 3.3.2: the retexturing tool gives
// each face its own area, filled with the part of the texture the face uses, which repeats where
// texture coordinates leave [0, 1]):
//   { "file": "wall.tga", "x": 1024, "y": 0, "width": 300, "height": 140,
//     "source_x": -37, "source_y": 250 }
// Destination texel (x + i, y + j), 0 <= i < width, 0 <= j < height, takes image texel
// ((source_x + i) mod w, (source_y + j) mod h), mod the non-negative remainder, w x h the image's
// size. width, height (1 to kMaxPlacedSide) default to w, h; source_x, source_y (integers within
// +-2^40) to 0; any of the four may be given alone, and any one makes a region placement, which
// is read whole (image_rows.h). Without them a placement shows its whole image once, streamed.

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/enum_names.h"
#include "format/texture_description.h"

namespace vt {

// How each level is made from the one above (thesis 3.3.1: "scaled down ... by bilinear
// filtering"; halving with bilinear sampling at the new texel centres is the 2x2 box).
enum class MipFilter {
  kBox,   // 2x2 average
  kTent,  // separable [1 3 3 1] / 8 over 4x4 texels: less aliasing, slightly softer
};

struct Placement {
  std::filesystem::path file;
  uint64_t x = 0, y = 0;  // texel position of the placed area's top-left texel, finest level
  uint32_t width = 0, height = 0;            // placed size: the image's, or the region's
  int64_t sourceX = 0, sourceY = 0;          // image texel shown at (x, y), before the modulo
  bool region = false;                       // any region field given: the image is read whole
  uint32_t imageWidth = 0, imageHeight = 0;  // from the image file
  uint32_t channels = 0;                     // from the image file
};

// The largest placed width or height: the widest texture the format allows.
inline constexpr uint64_t kMaxPlacedSide = levelSide(kMaxPageSize, kMaxLevel);
// Bound on |source_x|, |source_y|: sums with any placed offset stay far inside 64 bits.
inline constexpr int64_t kMaxSourceOffset = int64_t{1} << 40;

struct Layout {
  std::filesystem::path source;  // the layout file, or the single image
  TextureDescription description;
  MipFilter filter = MipFilter::kBox;
  std::array<uint8_t, 4> background = {0, 0, 0, 0};
  std::vector<Placement> images;
};

// Options of `vt build` that override the layout file's values or apply to a single image.
struct LayoutOverrides {
  std::optional<uint32_t> pageSize = std::nullopt;
  std::optional<uint32_t> border = std::nullopt;
  std::optional<uint32_t> channels = std::nullopt;
  std::optional<uint64_t> side = std::nullopt;
  std::optional<ColorSpace> colorSpace = std::nullopt;
  std::optional<MipFilter> filter = std::nullopt;
  std::optional<PixelFormat> format = std::nullopt;
};

// An image's size and channels, as its header states them.
struct ImageInfo {
  uint32_t width = 0, height = 0, channels = 0;
};

// Reads the header of `image` (OpenImageIO); throws InputError naming the image and `namedBy`
// (who asked for it) when it is missing, unreadable or empty.
ImageInfo probeImageFile(const std::filesystem::path& image, const std::string& namedBy);
using ImageProbe = std::function<ImageInfo(const std::filesystem::path&, const std::string&)>;

// Reads and validates a layout file: every distinct image is opened once (header only) for its
// size and channels, placements are checked against the texture and each other, and a region
// placement's image, decoded whole, must stay within kMaxWholeImageBytes
// (common/resource_limits.h). Throws InputError naming the layout file or the image and the
// problem; nothing is written.
Layout readLayout(const std::filesystem::path& file, const LayoutOverrides& overrides = {});

// The same for a layout's text held in memory: `file` names it in errors and image paths are
// relative to its folder; `probe` gives each distinct image's header.
Layout parseLayout(std::string_view text, const std::filesystem::path& file,
                   const LayoutOverrides& overrides, const ImageProbe& probe);

// A layout of one image at (0, 0).
Layout singleImageLayout(const std::filesystem::path& image, const LayoutOverrides& overrides = {});

// Layout files and `vt build` name the filter and the colour space so.
inline constexpr EnumNames<MipFilter, 2> kMipFilterNames = {{
    {MipFilter::kBox, "box"},
    {MipFilter::kTent, "tent"},
}};
inline constexpr EnumNames<ColorSpace, 2> kColorSpaceNames = {{
    {ColorSpace::kSrgb, "srgb"},
    {ColorSpace::kLinear, "linear"},
}};
// The stored pages' format: unorm8 texels of the texture's channels, or blocks (BC1 for opaque
// colour, BC3 where alpha matters) of RGBA.
inline constexpr EnumNames<PixelFormat, 3> kPageFormatNames = {{
    {PixelFormat::kUnorm8, "rgba8"},
    {PixelFormat::kBc1, "bc1"},
    {PixelFormat::kBc3, "bc3"},
}};

// Throw std::invalid_argument naming the field, the value and the table's names.
MipFilter parseMipFilter(const std::string& name);
ColorSpace parseColorSpace(const std::string& name);
PixelFormat parsePageFormat(const std::string& name);
std::string toString(MipFilter filter);

}  // namespace vt
