#pragma once
// Fixed-width little-endian encoding for file formats, independent of the host's byte order.

#include <bit>
#include <cstddef>
#include <cstdint>

namespace vt {

inline uint32_t loadU32(const std::byte* p) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | std::to_integer<uint32_t>(p[i]);
  return v;
}

inline uint64_t loadU64(const std::byte* p) {
  return loadU32(p) | (uint64_t{loadU32(p + 4)} << 32);
}

inline float loadF32(const std::byte* p) { return std::bit_cast<float>(loadU32(p)); }

inline void storeU32(std::byte* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = std::byte(static_cast<uint8_t>(v >> (8 * i)));
}

inline void storeU64(std::byte* p, uint64_t v) {
  storeU32(p, static_cast<uint32_t>(v));
  storeU32(p + 4, static_cast<uint32_t>(v >> 32));
}

inline void storeF32(std::byte* p, float v) { storeU32(p, std::bit_cast<uint32_t>(v)); }

}  // namespace vt
