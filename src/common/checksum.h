#pragma once
// The checksum of file sections and pages: XXH3, 64 bits (libxxhash). Fast enough to verify every
// page on every read (tens of GB/s), and a change of any bit changes it.

#include <cstddef>
#include <cstdint>
#include <span>

namespace vt {

uint64_t checksum64(std::span<const std::byte> bytes);

}  // namespace vt
