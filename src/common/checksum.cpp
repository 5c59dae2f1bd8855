#include "common/checksum.h"

#include <xxhash.h>

#include <cinttypes>
#include <cstdio>

namespace vt {

uint64_t checksum64(std::span<const std::byte> bytes) {
  return XXH3_64bits(bytes.data(), bytes.size());
}

std::string checksumText(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, value);
  return text;
}

}  // namespace vt
