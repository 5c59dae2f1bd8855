#pragma once
// A rendered frame as images for people: the colour, and the needbuffer by level (one hue per
// level, alternate pages darker, black where no geometry). Rows top to bottom, as image files
// store them (the frame's rows run bottom to top).

#include <cstdint>
#include <optional>
#include <vector>

#include "format/page_address.h"
#include "render/frame.h"
#include "shader/needbuffer.h"

namespace vt {

std::vector<uint8_t> colorImage(const Frame& frame);
std::vector<uint8_t> needImage(const Frame& frame, bool need8);

}  // namespace vt
