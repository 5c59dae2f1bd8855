#include "render/measured_table.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "common/checksum.h"
#include "common/delta_coding.h"
#include "common/error.h"
#include "common/input_file.h"

namespace vt {
namespace {

std::string checksumOf(const std::string& bytes) {
  return checksumText(
      checksum64(std::span(reinterpret_cast<const std::byte*>(bytes.data()), bytes.size())));
}

// 1 / x for x = m 2^e, m in [1, 2): r(m) 2^-e; IEEE division where that would leave the normal
// floats (|x| >= 2^126 gives a denormal reciprocal) or x is not a normal float.
float reciprocalOf(const std::vector<uint32_t>& table, float x) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const int exponent = static_cast<int>((bits >> 23) & 0xffu) - 127;
  if (exponent < -126 || exponent >= 126) return 1.0f / x;
  const float r = std::ldexp(std::bit_cast<float>(table[bits & 0x007fffffu]), -exponent);
  return (bits & 0x80000000u) ? -r : r;
}

// sqrt(x) for x = m 4^k, m in [1, 4): s(m) 2^k; IEEE sqrt for what is not a positive normal float.
float sqrtOf(const std::vector<uint32_t>& table, float x) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const int exponent = static_cast<int>((bits >> 23) & 0xffu) - 127;
  if ((bits & 0x80000000u) || exponent < -126 || exponent > 127) return std::sqrt(x);
  const int k = exponent >= 0 ? exponent / 2 : -((1 - exponent) / 2);  // floor(exponent / 2)
  // m = x 4^-k in [1, 4): the mantissa with exponent (exponent - 2k), 0 or 1.
  const uint32_t m = (bits & 0x007fffffu) | (static_cast<uint32_t>(127 + exponent - 2 * k) << 23);
  return std::ldexp(std::bit_cast<float>(table[m - MeasuredTable::kSqrtFirst]), k);
}

// log2(x) for x = m 2^e, m in [1, 2): e + l(m) in one float addition; -infinity for zero and
// denormals, NaN below zero, the input itself for infinity and NaN.
float log2Of(const std::vector<uint32_t>& table, float x) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const uint32_t field = (bits >> 23) & 0xffu;
  if (field == 0xffu) return (bits & 0x80000000u) && !std::isnan(x) ? std::nanf("") : x;
  if ((bits & 0x7fffffffu) != 0 && (bits & 0x80000000u)) return std::nanf("");
  if (field == 0) return -std::numeric_limits<float>::infinity();
  const float e = static_cast<float>(static_cast<int>(field) - 127);
  return e + std::bit_cast<float>(table[bits & 0x007fffffu]);
}

}  // namespace

uint32_t MeasuredTable::first(TabledFunction f) {
  switch (f) {
    case TabledFunction::kReciprocal:
      return kReciprocalFirst;
    case TabledFunction::kSqrt:
      return kSqrtFirst;
    case TabledFunction::kLog2:
      break;
  }
  return kLog2First;
}
uint32_t MeasuredTable::count(TabledFunction f) {
  switch (f) {
    case TabledFunction::kReciprocal:
      return kReciprocalCount;
    case TabledFunction::kSqrt:
      return kSqrtCount;
    case TabledFunction::kLog2:
      break;
  }
  return kLog2Count;
}

const char* tableKey(TabledFunction f) {
  switch (f) {
    case TabledFunction::kReciprocal:
      return "reciprocal";
    case TabledFunction::kSqrt:
      return "sqrt";
    case TabledFunction::kLog2:
      break;
  }
  return "log2_table";
}

std::string tableFileName(TabledFunction f, const std::string& checksum) {
  return std::string(tableKey(f)) + "-" + checksum + ".table";
}

MeasuredTable::MeasuredTable(TabledFunction f, std::vector<uint32_t> bits)
    : function_(f), bits_(std::move(bits)) {
  if (bits_.size() != count(f))
    throw std::invalid_argument(std::string("measured ") + tableKey(f) +
                                ": not one result per float of its interval");
  // Where the exact function's values over the interval lie.
  const float lo = f == TabledFunction::kReciprocal ? 0.5f
                   : f == TabledFunction::kSqrt     ? 1.0f
                                                    : 0.0f;
  const float hi = f == TabledFunction::kSqrt ? 2.0f : 1.0f;
  for (const uint32_t b : bits_) {
    const float r = std::bit_cast<float>(b);
    if (!(r >= lo && r <= hi))
      throw std::invalid_argument(std::string("measured ") + tableKey(f) + ": a result outside [" +
                                  std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  checksum_ = checksumOf(deltaCoded(bits_));
}

float MeasuredTable::of(float x) const {
  switch (function_) {
    case TabledFunction::kReciprocal:
      return reciprocalOf(bits_, x);
    case TabledFunction::kSqrt:
      return sqrtOf(bits_, x);
    case TabledFunction::kLog2:
      break;
  }
  return log2Of(bits_, x);
}

std::string MeasuredTable::fileBytes() const { return deltaCoded(bits_); }

std::shared_ptr<const MeasuredTable> MeasuredTable::read(TabledFunction f,
                                                         const std::filesystem::path& file,
                                                         const std::string& checksum) {
  const uint64_t bytesExpected = uint64_t{count(f)} * sizeof(uint32_t);
  const std::string what = std::string("measured ") + tableKey(f) + " table";
  const std::string bytes = readTextFile(file, what, bytesExpected);
  if (bytes.size() != bytesExpected)
    throw InputError(file, what + ": " + std::to_string(bytes.size()) + " bytes, expected " +
                               std::to_string(bytesExpected));
  if (checksumOf(bytes) != checksum)
    throw InputError(file, what + ": checksum " + checksumOf(bytes) + ", the model names " +
                               checksum + " (another table?)");
  std::vector<uint32_t> bits = deltaDecoded(bytes);
  try {
    return std::make_shared<const MeasuredTable>(f, std::move(bits));
  } catch (const std::invalid_argument& e) {
    throw InputError(file, e.what());
  }
}

}  // namespace vt
