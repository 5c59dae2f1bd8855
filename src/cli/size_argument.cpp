#include "cli/size_argument.h"

#include <stdexcept>

#include "cli/argument_checks.h"
#include "scene/camera.h"

namespace vt {

Viewport parseSize(const std::string& text) {
  // Digits only, and at most five of them per side: "%d" would wrap 4294967360 to 64.
  const auto side = [&](size_t from, size_t to) {
    const std::string digits = text.substr(from, to - from);
    if (digits.empty() || digits.size() > 5 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      return 0;
    return std::stoi(digits);
  };
  const size_t x = text.find('x');
  const int width = x == std::string::npos ? 0 : side(0, x),
            height = x == std::string::npos ? 0 : side(x + 1, text.size());
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw std::invalid_argument("size: '" + text + "' is not WIDTHxHEIGHT within 1..16384");
  return {width, height};
}

CLI::Validator sizeValidator() { return validatorFrom(parseSize, "SIZE"); }
CLI::Validator cameraValidator() { return validatorFrom(parseCamera, "CAMERA"); }

}  // namespace vt
