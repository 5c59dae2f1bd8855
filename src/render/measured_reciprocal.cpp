#include "render/measured_reciprocal.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "common/checksum.h"
#include "common/error.h"
#include "common/input_file.h"

namespace vt {
namespace {

static_assert(std::endian::native == std::endian::little, "table files are little-endian");

std::string deltaCoded(const std::vector<uint32_t>& bits) {
  std::string bytes(bits.size() * sizeof(uint32_t), '\0');
  uint32_t previous = 0;
  for (size_t i = 0; i < bits.size(); ++i) {
    const uint32_t delta = bits[i] - previous;
    std::memcpy(bytes.data() + i * sizeof(uint32_t), &delta, sizeof delta);
    previous = bits[i];
  }
  return bytes;
}

std::string checksumOf(const std::string& bytes) {
  return checksumText(
      checksum64(std::span(reinterpret_cast<const std::byte*>(bytes.data()), bytes.size())));
}

}  // namespace

MeasuredReciprocal::MeasuredReciprocal(std::vector<uint32_t> bits) : bits_(std::move(bits)) {
  if (bits_.size() != kCount)
    throw std::invalid_argument("measured reciprocal: not one result per float of [1, 2)");
  for (const uint32_t b : bits_) {
    const float r = std::bit_cast<float>(b);
    if (!(r >= 0.5f && r <= 1.0f))
      throw std::invalid_argument("measured reciprocal: a result outside [0.5, 1]");
  }
  checksum_ = checksumOf(deltaCoded(bits_));
}

float MeasuredReciprocal::of(float q) const {
  const uint32_t bits = std::bit_cast<uint32_t>(q);
  const int exponent = static_cast<int>((bits >> 23) & 0xffu) - 127;
  // Zero, denormals, infinities and NaN; and |q| >= 2^126, whose reciprocal would be denormal.
  if (exponent < -126 || exponent >= 126) return 1.0f / q;
  const uint32_t mantissa = bits & 0x007fffffu;
  const float r = std::ldexp(std::bit_cast<float>(bits_[mantissa]), -exponent);  // exact: normal
  return (bits & 0x80000000u) ? -r : r;
}

std::string MeasuredReciprocal::fileBytes() const { return deltaCoded(bits_); }

std::shared_ptr<const MeasuredReciprocal> MeasuredReciprocal::read(
    const std::filesystem::path& file, const std::string& checksum) {
  constexpr uint64_t kBytes = uint64_t{kCount} * sizeof(uint32_t);
  const std::string bytes = readTextFile(file, "measured reciprocal table", kBytes);
  if (bytes.size() != kBytes)
    throw InputError(file, "measured reciprocal table: " + std::to_string(bytes.size()) +
                               " bytes, expected " + std::to_string(kBytes));
  if (checksumOf(bytes) != checksum)
    throw InputError(file, "measured reciprocal table: checksum " + checksumOf(bytes) +
                               ", the model names " + checksum + " (another table?)");
  std::vector<uint32_t> bits(kCount);
  uint32_t previous = 0;
  for (size_t i = 0; i < bits.size(); ++i) {
    uint32_t delta;
    std::memcpy(&delta, bytes.data() + i * sizeof(uint32_t), sizeof delta);
    bits[i] = previous + delta;
    previous = bits[i];
  }
  try {
    return std::make_shared<const MeasuredReciprocal>(std::move(bits));
  } catch (const std::invalid_argument& e) {
    throw InputError(file, e.what());
  }
}

}  // namespace vt
