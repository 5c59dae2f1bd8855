#pragma once
// `vt demo`, the project's main job on its bundled default scene, in one call: generate the
// default scene's material images and layout, build its virtual texture with `vt build`'s builder,
// read it back, verify every page, print its summary and write one level as an image; then render
// the box room with the CPU oracle and with OpenGL (llvmpipe when no GPU) from the same cache
// state and compare the two frames pixel by pixel. Everything goes into a temporary folder that
// takes the output's place once complete: a failure leaves the previous output or none.

#include <filesystem>
#include <ostream>

namespace vt {

// `output` must be a folder the caller may replace (common/output_path.h); messages name the
// files by their final paths.
void runDemo(const std::filesystem::path& output, std::ostream& out);

}  // namespace vt
