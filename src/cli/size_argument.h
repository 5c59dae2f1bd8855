#pragma once
// The WIDTHxHEIGHT and camera arguments of the rendering commands, checked by CLI11 so that a
// malformed value is a bad argument (usage line, exit code 2).

#include <CLI/CLI.hpp>
#include <string>

#include "scene/clip_space_mesh.h"

namespace vt {

// Parses "WIDTHxHEIGHT" with both in [1, 16384]; throws std::invalid_argument naming the text.
Viewport parseSize(const std::string& text);

// A CLI11 validator running parseSize.
CLI::Validator sizeValidator();
// A CLI11 validator running parseCamera (scene/camera.h).
CLI::Validator cameraValidator();

}  // namespace vt
