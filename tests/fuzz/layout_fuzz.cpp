// Fuzz target: layout files of `vt build` (build/layout.h), and what the build derives from a
// layout before it reads any image: the row rings' memory.

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <string>
#include <string_view>

#include "build/layout.h"
#include "build/texture_builder.h"
#include "fuzz/fuzz_targets.h"

namespace vt::fuzz {
namespace {

// The image a name stands for (fuzz_targets.h): "WxHxC..." or 64 x 64 x 3; "missing..." fails.
ImageInfo imageNamed(const std::filesystem::path& image, const std::string& namedBy) {
  const std::string name = image.filename().string();
  if (name.starts_with("missing"))
    throw InputError(image, "image not found (named by " + namedBy + ")");
  uint32_t width = 0, height = 0, channels = 0;
  if (std::sscanf(name.c_str(), "%" SCNu32 "x%" SCNu32 "x%" SCNu32, &width, &height, &channels) !=
      3)
    return {64, 64, 3};
  return {std::max(width, 1u), std::max(height, 1u), std::clamp(channels, 1u, 16u)};
}

}  // namespace

void layoutFile(Input input) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  const Layout layout = parseLayout(text, "/nonexistent/vt-fuzz/layout.json", {}, imageNamed);
  ringBytesBound(layout);
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::layoutFile)
