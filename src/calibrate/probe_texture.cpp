#include "calibrate/probe_texture.h"

#include "build/synthetic_texture.h"

namespace vt::calibrate {

TextureDescription ProbeTexture::describe(int levelCount) {
  return {
      .pageSize = 16, .border = 2, .levelCount = static_cast<uint32_t>(levelCount), .channels = 4};
}

ProbeTexture::ProbeTexture(int levelCount)
    : description_(describe(levelCount)),
      texture_(description_, [this](PageId page) { return syntheticPage(description_, page); }) {}

}  // namespace vt::calibrate
