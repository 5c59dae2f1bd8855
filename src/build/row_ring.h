#pragma once
// The last `capacity` texel rows of one level, in a ring: the only part of a level the builder
// ever holds. Row q lives in slot q mod capacity until row q + capacity replaces it.
//
// Texels no image influences hold the background, and are not stored. The columns are cut into
// strips of kStripTexels; a strip holds its columns for every slot and exists only while a held
// row wrote into it:
//
//        columns:  0 .. 255   256 .. 511   512 .. 767   ...
//   slot 0         [strip 3]  background   [strip 0]
//   slot 1         [strip 3]  background   [strip 0]     (a strip: capacity x 256 texels)
//   ...
//
// A strip is made (from a pool of free ones, all background) when a row declares a write into its
// columns, and goes back to the pool once `capacity` rows have passed without a write into it.
// So memory follows what the images touch within `capacity` rows, never the texture's width: a
// 1 x 1 image placed near column 2^22 costs one strip per level. Each slot remembers which columns
// its row wrote, so a new row restores only those: work follows the images too.

#include <array>
#include <cstdint>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

namespace vt {

struct ColumnSpan {
  uint64_t begin = 0, end = 0;  // texel columns [begin, end)
};

class RowRing {
 public:
  static constexpr uint64_t kStripTexels = 256;

  RowRing(uint64_t side, uint32_t channels, uint32_t capacity,
          const std::array<uint8_t, 4>& background);

  // Starts row q (rows arrive in order): restores the background where the slot's previous row
  // wrote, and returns strips no held row wrote into to the pool.
  void append(uint64_t q);
  // Declares that the current row writes columns `span`: makes their strips. Only then may they
  // be written, through writable() or write(); declaring is not thread-safe, writing different
  // columns of declared strips is.
  void declare(ColumnSpan span);
  // Texel x of the current row, and the texels after it up to the end of its strip.
  uint8_t* writable(uint64_t x);
  // Copies `count` texels to the current row from column x on (declared columns).
  void write(uint64_t x, const uint8_t* texels, uint64_t count);

  // Texel x of row q, which must still be held.
  const uint8_t* texel(uint64_t q, uint64_t x) const {
    const uint64_t slot = slotOf(q);
    const uint32_t strip = stripOfColumn_[x / kStripTexels];
    if (strip == kNoStrip) return background_.data();
    return strips_[strip].data() + (slot * kStripTexels + x % kStripTexels) * channels_;
  }
  // Copies texels [begin, begin + count) of row q to out.
  void read(uint64_t q, uint64_t begin, uint64_t count, uint8_t* out) const;

  uint64_t rowsReceived() const { return rows_; }
  uint64_t side() const { return side_; }
  uint32_t channels() const { return channels_; }
  // Bytes held now, and the most held at once: the strips made (in use or pooled), the column
  // table and the written-column lists.
  uint64_t bytes() const;
  // Bytes of one strip.
  uint64_t stripBytes() const { return capacity_ * kStripTexels * channels_; }

 private:
  static constexpr uint32_t kNoStrip = UINT32_MAX;

  uint64_t slotOf(uint64_t q) const {
    if (q >= rows_ || q + capacity_ < rows_)
      throw std::logic_error("RowRing: row " + std::to_string(q) + " is not held");
    return q % capacity_;
  }

  uint64_t side_;
  uint32_t channels_;
  uint64_t capacity_;
  std::array<uint8_t, 4> background_;
  std::vector<uint32_t> stripOfColumn_;           // per kStripTexels columns: strip or kNoStrip
  std::vector<std::vector<uint8_t>> strips_;      // every strip made, in use or pooled
  std::vector<uint64_t> stripColumn_;             // per strip: its index in stripOfColumn_
  std::vector<uint64_t> stripLastRow_;            // per strip: the last row that wrote into it
  std::vector<uint32_t> pool_;                    // strips free for reuse (all background)
  std::deque<std::pair<uint32_t, uint64_t>> writes_;  // (strip, row), rows rising: retirements
  std::vector<std::vector<ColumnSpan>> written_;  // per slot
  uint64_t rows_ = 0;
};

}  // namespace vt
