#pragma once
// The small synthetic virtual texture the oracle draws calibration and fingerprint probes with,
// made in memory (build/synthetic_texture.h), every page resident. What the probes compare
// (which triangle, texture coordinates, derivatives, depth) does not depend on its texels.

#include "reference/texture_source.h"

namespace vt::calibrate {

class ProbeTexture {
 public:
  explicit ProbeTexture(int levelCount);

  const reference::ResidentTexture& texture() const { return texture_; }

 private:
  const reference::ResidentTexture texture_;
};

}  // namespace vt::calibrate
