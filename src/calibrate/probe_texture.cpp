#include "calibrate/probe_texture.h"

#include <stdlib.h>

#include <stdexcept>
#include <string>

#include "build/synthetic_texture.h"

namespace vt::calibrate {

ProbeTexture::ProbeTexture(int levelCount) {
  std::string pattern = (std::filesystem::temp_directory_path() / "vt-probes-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a scratch folder");
  folder_ = pattern;
  try {
    writeSyntheticTexture(folder_ / "t.vt", {{.pageSize = 16,
                                              .border = 2,
                                              .levelCount = static_cast<uint32_t>(levelCount),
                                              .channels = 4},
                                             std::nullopt});
    reader_ = std::make_unique<VirtualTextureReader>(folder_ / "t.vt");
    texture_ = std::make_unique<reference::ResidentTexture>(*reader_);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
    throw;
  }
}

ProbeTexture::~ProbeTexture() {
  texture_.reset();
  reader_.reset();
  std::error_code ignored;
  std::filesystem::remove_all(folder_, ignored);
}

}  // namespace vt::calibrate
