#pragma once
// A measured table as a member of a family (render/arithmetic.h): a function an implementation
// computes, taken from the probe pack's sweep of it (probes/function_sweeps.h) where no closed
// form reproduces it.
//
//   reciprocal  1.0 / x over every float of [1, 2). For x = m 2^e with m in [1, 2), 1 / x is the
//               table's r(m) times 2^-e, and -x gives -(1 / x).
//   sqrt        sqrt(x) over every float of [1, 4). For x = m 4^k with m in [1, 4), sqrt(x) is the
//               table's s(m) times 2^k.
//   log2        log2(x) over every float of [1, 2). For x = m 2^e with m in [1, 2), log2(x) is
//               e + l(m) in one float addition (exact for e = 0); zero and denormals give
//               -infinity, as a flushing implementation's log2 of 0 does.
// One interval decides every normal input of an implementation that reduces its range by the
// exponent, as function units do; the scaling is exact while the result is a normal float. Zero,
// denormal, negative, infinite and NaN inputs, and results that would not be normal, take the
// closed form (IEEE division, IEEE sqrt): the oracle's probes never ask for them. Whether the
// extension holds is not assumed: the calibration takes a table only where probes beyond its
// interval are reproduced with it (the perspective triangles for the reciprocal, whose 1/w spans
// many binades, calibrate/raster_fit.h; for sqrt and log2 their 65,536 samples of every
// exponent and, for log2, the sweep's other binade [0.5, 1), calibrate/shader_math_fit.h).
//
// The table travels beside the model file (precision_model_file.h) as its own file, FUNCTION-
// CHECKSUM.table: the results' bits delta-coded as the sweep's file is (each minus its
// predecessor, little-endian uint32), named by the XXH3 checksum of those bytes.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace vt {

enum class TabledFunction { kReciprocal, kSqrt, kLog2 };

class MeasuredTable {
 public:
  static constexpr uint32_t kReciprocalFirst = 0x3f800000u;          // 1.0f
  static constexpr uint32_t kReciprocalCount = uint32_t{1} << 23;    // every float of [1, 2)
  static constexpr uint32_t kSqrtFirst = 0x3f800000u;                // 1.0f
  static constexpr uint32_t kSqrtCount = uint32_t{1} << 24;          // every float of [1, 4)
  static constexpr uint32_t kLog2First = 0x3f800000u;                // 1.0f
  static constexpr uint32_t kLog2Count = uint32_t{1} << 23;          // every float of [1, 2)
  static uint32_t first(TabledFunction f);
  static uint32_t count(TabledFunction f);

  // `bits`: the result bits for x = bit_cast<float>(first(f) + i), i < count(f); each must lie
  // where the exact function's values over the interval lie, [0.5, 1], [1, 2] or [0, 1]
  // (std::invalid_argument otherwise).
  MeasuredTable(TabledFunction f, std::vector<uint32_t> bits);

  float of(float x) const;
  TabledFunction function() const { return function_; }
  // The XXH3 checksum of the table's file bytes, 16 hexadecimal digits (common/checksum.h).
  const std::string& checksum() const { return checksum_; }
  const std::vector<uint32_t>& bits() const { return bits_; }

  // The file's bytes: the results delta-coded.
  std::string fileBytes() const;
  // Reads `file` (exactly count(f) * 4 bytes) and checks it against `checksum`; InputError naming
  // the file otherwise.
  static std::shared_ptr<const MeasuredTable> read(TabledFunction f,
                                                   const std::filesystem::path& file,
                                                   const std::string& checksum);

 private:
  TabledFunction function_;
  std::vector<uint32_t> bits_;
  std::string checksum_;
};

// "reciprocal", "sqrt" or "log2_table": the table's key in model files (log2's own key names its
// closest closed form) and the start of its file's name.
const char* tableKey(TabledFunction f);
// FUNCTION-CHECKSUM.table, the file beside the model.
std::string tableFileName(TabledFunction f, const std::string& checksum);

}  // namespace vt
