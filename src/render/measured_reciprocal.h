#pragma once
// A measured table as a member of a family (render/arithmetic.h): the reciprocal an implementation
// computes, taken from the probe pack's sweep of 1.0 / x over every float of [1, 2)
// (probes/function_sweeps.h) where no closed form reproduces it.
//
// One binade decides every normal input where the implementation reduces its range by the
// exponent, as reciprocal units do: for q = m 2^e with m in [1, 2), 1 / q is the table's r(m)
// times 2^-e (exact while the result is a normal float), and -q gives -(1 / q). Zero, denormal,
// infinite and NaN inputs, and results that would not be normal, take IEEE division: the oracle
// never divides by them where a probe could check it. Whether the extension holds is not assumed:
// the calibration takes the table only where the perspective triangles, whose 1/w spans many
// binades, are reproduced with it (calibrate/raster_fit.h).
//
// The table travels beside the model file (precision_model_file.h) as its own file: the results'
// bits delta-coded as the sweep's file is (each minus its predecessor, little-endian uint32), and
// the model names it with the XXH3 checksum of those bytes.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace vt {

class MeasuredReciprocal {
 public:
  static constexpr uint32_t kFirst = 0x3f800000u;    // 1.0f
  static constexpr uint32_t kCount = uint32_t{1} << 23;  // every float of [1, 2)

  // `bits`: the result bits of 1.0 / x for x = bit_cast<float>(kFirst + i), i < kCount; each must
  // be a float in [0.5, 1] (std::invalid_argument otherwise: no reciprocal of [1, 2) is outside).
  explicit MeasuredReciprocal(std::vector<uint32_t> bits);

  float of(float q) const;
  // The XXH3 checksum of the table's file bytes, 16 hexadecimal digits (common/checksum.h).
  const std::string& checksum() const { return checksum_; }
  const std::vector<uint32_t>& bits() const { return bits_; }

  // The file's bytes: the results delta-coded.
  std::string fileBytes() const;
  // Reads `file` (exactly kCount * 4 bytes) and checks it against `checksum`; InputError naming
  // the file otherwise.
  static std::shared_ptr<const MeasuredReciprocal> read(const std::filesystem::path& file,
                                                        const std::string& checksum);

 private:
  std::vector<uint32_t> bits_;
  std::string checksum_;
};

}  // namespace vt
