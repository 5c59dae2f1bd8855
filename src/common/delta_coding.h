#pragma once
// 32-bit values stored as the differences of neighbours (modulo 2^32), little-endian: a sweep of
// a smooth function over consecutive floats then holds mostly small, repeated differences, which
// compress well in transit (capture/sweep_files.h, render/measured_table.h).

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

static_assert(std::endian::native == std::endian::little, "delta-coded files are little-endian");

// The bytes of `values` delta-coded: value i - value i-1, the first against 0.
inline std::string deltaCoded(const std::vector<uint32_t>& values) {
  std::string bytes(values.size() * sizeof(uint32_t), '\0');
  uint32_t previous = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    const uint32_t delta = values[i] - previous;
    std::memcpy(bytes.data() + i * sizeof(uint32_t), &delta, sizeof delta);
    previous = values[i];
  }
  return bytes;
}

// The values of delta-coded bytes (whole 4-byte values; a trailing part is ignored).
inline std::vector<uint32_t> deltaDecoded(std::string_view bytes) {
  std::vector<uint32_t> values(bytes.size() / sizeof(uint32_t));
  uint32_t previous = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    uint32_t delta;
    std::memcpy(&delta, bytes.data() + i * sizeof(uint32_t), sizeof delta);
    values[i] = previous + delta;
    previous = values[i];
  }
  return values;
}

}  // namespace vt
