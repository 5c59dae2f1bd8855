#pragma once
// The GLSL source of the virtual-texture fragment shader: the GL backend's fetch functions, then
// the shared shader logic (src/shader/*.glsl) verbatim, then main(). The indirection table is an
// integer texture whose mip level L - m holds the entries of page level m; the page cache is an
// RGBA8 texture.

#include <string>

namespace vt {

std::string virtualTextureFragmentSource();
std::string virtualTextureVertexSource();

}  // namespace vt
