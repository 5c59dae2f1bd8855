#pragma once
// The small synthetic virtual texture the oracle draws calibration and fingerprint probes with:
// written to a scratch folder, read back, every page resident, and removed with the object.
// What the probes compare (which triangle, texture coordinates, derivatives, depth) does not
// depend on its texels.

#include <filesystem>
#include <memory>

#include "format/virtual_texture_reader.h"
#include "reference/texture_source.h"

namespace vt::calibrate {

class ProbeTexture {
 public:
  explicit ProbeTexture(int levelCount);
  ~ProbeTexture();
  ProbeTexture(const ProbeTexture&) = delete;
  ProbeTexture& operator=(const ProbeTexture&) = delete;

  const reference::ResidentTexture& texture() const { return *texture_; }

 private:
  std::filesystem::path folder_;
  std::unique_ptr<VirtualTextureReader> reader_;
  std::unique_ptr<reference::ResidentTexture> texture_;
};

}  // namespace vt::calibrate
