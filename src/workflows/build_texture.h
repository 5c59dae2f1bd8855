#pragma once
// `vt build`'s work as one call (thesis 3.3.1): a layout file or a single image, with the
// command line's overrides, built into a virtual-texture file (build/texture_builder.h), after
// checking that the output destroys none of the images it reads; one line of what was built.

#include <filesystem>
#include <ostream>

#include "build/layout.h"
#include "build/texture_builder.h"

namespace vt {

struct BuildRequest {
  std::filesystem::path input;  // a layout (.json) or an image
  LayoutOverrides overrides;
  BuildOptions options;
  std::filesystem::path output;
};

void buildTexture(const BuildRequest& request, std::ostream& out);

}  // namespace vt
