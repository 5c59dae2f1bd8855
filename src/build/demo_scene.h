#pragma once
// The default scene of `vt demo` until a retextured mesh replaces it: five generated material
// images (bricks, planks, tiles, sky, marble) of assorted sizes, none a power of two on both
// sides, and a layout placing them with gaps on a 4096^2 texture, so that the build exercises
// borders, sparse pages and every level. The same call writes the same bytes (with the same C
// math library: the patterns use sin and pow).

#include <filesystem>

namespace vt {

// Writes the images and "layout.json" into `folder`; returns the layout file.
std::filesystem::path writeDemoScene(const std::filesystem::path& folder);

}  // namespace vt
