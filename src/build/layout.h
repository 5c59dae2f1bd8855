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
//     "background": [0, 0, 0, 0],  // texels no image covers (default transparent black)
//     "images": [ { "file": "wall.tga", "x": 0, "y": 0 }, ... ]
//   }
// x grows with s, y with t (rows of the texture, top row of each image first). Images must not
// overlap and must lie inside the texture.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

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
  uint64_t x = 0, y = 0;           // texel position of the image's top-left texel, finest level
  uint32_t width = 0, height = 0;  // from the image file
  uint32_t channels = 0;           // from the image file
};

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
};

// Reads and validates a layout file: every image is opened (header only) for its size and
// channels, placements are checked against the texture and each other. Throws InputError naming
// the layout file or the image and the problem; nothing is written.
Layout readLayout(const std::filesystem::path& file, const LayoutOverrides& overrides = {});

// A layout of one image at (0, 0).
Layout singleImageLayout(const std::filesystem::path& image, const LayoutOverrides& overrides = {});

MipFilter parseMipFilter(const std::string& name);  // throws std::invalid_argument
ColorSpace parseColorSpace(const std::string& name);
std::string toString(MipFilter filter);

}  // namespace vt
