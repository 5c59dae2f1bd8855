#include "cli/size_argument.h"

#include <cstdio>
#include <stdexcept>

#include "scene/camera.h"

namespace vt {

Viewport parseSize(const std::string& text) {
  int width = 0, height = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 || x != 'x' ||
      width < 1 || height < 1 || width > 16384 || height > 16384)
    throw std::invalid_argument("size: '" + text + "' is not WIDTHxHEIGHT within 1..16384");
  return {width, height};
}

namespace {

// A validator that reports the std::invalid_argument of `parse` as CLI11's error text.
template <class Parse>
CLI::Validator validatorFrom(Parse parse, const char* name) {
  return CLI::Validator(
      [parse](std::string& text) {
        try {
          parse(text);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      },
      name);
}

}  // namespace

CLI::Validator sizeValidator() { return validatorFrom(parseSize, "SIZE"); }
CLI::Validator cameraValidator() { return validatorFrom(parseCamera, "CAMERA"); }

}  // namespace vt
