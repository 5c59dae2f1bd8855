#pragma once
// The last `capacity` texel rows of one level, in a ring: the only part of a level the builder
// ever holds. Row q lives in slot q mod capacity until row q + capacity replaces it.
//
// Texels no image influences hold the background. The ring starts filled with it and remembers
// which columns each slot's row wrote, so a new row only restores those: work follows the images,
// not the texture's width, and a sparse texture of 65536^2 texels costs what its images cost.

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace vt {

struct ColumnSpan {
  uint64_t begin = 0, end = 0;  // texel columns [begin, end)
};

class RowRing {
 public:
  RowRing(uint64_t side, uint32_t channels, uint32_t capacity,
          const std::array<uint8_t, 4>& background);

  // Starts row q (rows arrive in order): restores the background where the slot's previous row
  // wrote, and returns the slot. Columns the caller then writes must be declared with wrote().
  uint8_t* append(uint64_t q);
  void wrote(ColumnSpan span);

  // Row q, which must still be held.
  const uint8_t* row(uint64_t q) const {
    if (q >= rows_ || q + capacity_ < rows_)
      throw std::logic_error("RowRing: row " + std::to_string(q) + " is not held");
    return texels_.data() + (q % capacity_) * rowBytes_;
  }

  uint64_t rowsReceived() const { return rows_; }
  uint64_t bytes() const { return texels_.size(); }

 private:
  uint32_t channels_;
  uint64_t rowBytes_;
  uint64_t capacity_;
  std::array<uint8_t, 4> background_;
  std::vector<uint8_t> texels_;
  std::vector<std::vector<ColumnSpan>> written_;  // per slot
  uint64_t rows_ = 0;
};

}  // namespace vt
