#pragma once
// The last `capacity` texel rows of one level, in a ring: the only part of a level the builder
// ever holds. Row q lives in slot q mod capacity until row q + capacity replaces it.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace vt {

class RowRing {
 public:
  RowRing(uint64_t side, uint32_t channels, uint32_t capacity)
      : rowBytes_(side * channels), capacity_(capacity), texels_(rowBytes_ * capacity) {}

  // The slot for row q, which becomes the newest row.
  uint8_t* append(uint64_t q) {
    if (q != rows_) throw std::logic_error("RowRing: rows must arrive in order");
    ++rows_;
    return slot(q);
  }

  // Row q, which must still be held.
  const uint8_t* row(uint64_t q) const {
    if (q >= rows_ || q + capacity_ < rows_)
      throw std::logic_error("RowRing: row " + std::to_string(q) + " is not held (rows " +
                             std::to_string(rows_ > capacity_ ? rows_ - capacity_ : 0) + ".." +
                             std::to_string(rows_) + ")");
    return texels_.data() + (q % capacity_) * rowBytes_;
  }

  uint64_t rowsReceived() const { return rows_; }
  uint64_t bytes() const { return texels_.size(); }

 private:
  uint8_t* slot(uint64_t q) { return texels_.data() + (q % capacity_) * rowBytes_; }

  uint64_t rowBytes_;
  uint64_t capacity_;
  std::vector<uint8_t> texels_;
  uint64_t rows_ = 0;
};

}  // namespace vt
