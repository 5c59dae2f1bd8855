#include "common/checksum.h"

#include <xxhash.h>

namespace vt {

uint64_t checksum64(std::span<const std::byte> bytes) {
  return XXH3_64bits(bytes.data(), bytes.size());
}

}  // namespace vt
