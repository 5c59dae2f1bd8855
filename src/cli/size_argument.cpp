#include "cli/size_argument.h"

#include <cstdio>
#include <stdexcept>

namespace vt {

Viewport parseSize(const std::string& text) {
  int width = 0, height = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 || x != 'x' ||
      width < 1 || height < 1 || width > 16384 || height > 16384)
    throw std::invalid_argument("size: '" + text + "' is not WIDTHxHEIGHT within 1..16384");
  return {width, height};
}

CLI::Validator sizeValidator() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          parseSize(text);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      },
      "SIZE");
}

}  // namespace vt
