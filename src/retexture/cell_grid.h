#pragma once
// A square grid of page-sized cells for first-fit placement (the thesis's layout grid, 3.3.2.1).

#include <cstdint>
#include <optional>
#include <vector>

namespace vt {

class CellGrid {
 public:
  struct Cell {
    uint64_t x = 0, y = 0;
  };

  explicit CellGrid(uint64_t side);

  uint64_t side() const { return side_; }
  // The first free block of w x h cells in row-major order of its top-left cell.
  std::optional<Cell> firstFit(uint64_t w, uint64_t h) const;
  void occupy(Cell at, uint64_t w, uint64_t h);
  // Enlarges the grid to `side` cells per side; occupied cells keep their positions.
  void grow(uint64_t side);

 private:
  bool used(uint64_t x, uint64_t y) const { return used_[y * side_ + x] != 0; }

  uint64_t side_;
  std::vector<uint8_t> used_;
  std::vector<uint64_t> freeInRow_;  // free cells per row, to skip full rows
};

}  // namespace vt
