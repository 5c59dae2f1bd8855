#include "calibrate/probe_texture.h"

#include "build/synthetic_texture.h"

namespace vt::calibrate {
namespace {

reference::ResidentTexture probeTexture(int levelCount) {
  const TextureDescription description{.pageSize = 16,
                                       .border = 2,
                                       .levelCount = static_cast<uint32_t>(levelCount),
                                       .channels = 4};
  return reference::ResidentTexture(
      description, [description](PageId page) { return syntheticPage(description, page); });
}

}  // namespace

ProbeTexture::ProbeTexture(int levelCount) : texture_(probeTexture(levelCount)) {}

}  // namespace vt::calibrate
