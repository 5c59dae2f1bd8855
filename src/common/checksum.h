#pragma once
// The checksum of file sections and pages: XXH3, 64 bits (libxxhash). Fast enough to verify every
// page on every read (tens of GB/s), and a change of any bit changes it.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace vt {

uint64_t checksum64(std::span<const std::byte> bytes);

// A checksum or identity as files and reports write it: 16 lowercase hexadecimal digits.
std::string checksumText(uint64_t value);

}  // namespace vt
