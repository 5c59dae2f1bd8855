#include "retexture/cell_grid.h"

namespace vt {

CellGrid::CellGrid(uint64_t side) : side_(side), used_(side * side, 0), freeInRow_(side, side) {}

std::optional<CellGrid::Cell> CellGrid::firstFit(uint64_t w, uint64_t h) const {
  if (w > side_ || h > side_) return std::nullopt;
  for (uint64_t y = 0; y + h <= side_; ++y) {
    if (freeInRow_[y] < w) continue;
    for (uint64_t x = 0; x + w <= side_;) {
      // Find an occupied cell in the block; skip past it, or take the block.
      uint64_t blockedAt = side_;
      for (uint64_t dy = 0; dy < h && blockedAt == side_; ++dy)
        for (uint64_t dx = w; dx-- > 0;)
          if (used(x + dx, y + dy)) {
            blockedAt = x + dx;
            break;
          }
      if (blockedAt == side_) return Cell{x, y};
      x = blockedAt + 1;
    }
  }
  return std::nullopt;
}

void CellGrid::occupy(Cell at, uint64_t w, uint64_t h) {
  for (uint64_t y = at.y; y < at.y + h; ++y) {
    for (uint64_t x = at.x; x < at.x + w; ++x) used_[y * side_ + x] = 1;
    freeInRow_[y] -= w;
  }
}

void CellGrid::grow(uint64_t side) {
  std::vector<uint8_t> used(side * side, 0);
  std::vector<uint64_t> freeInRow(side, side);
  for (uint64_t y = 0; y < side_; ++y) {
    for (uint64_t x = 0; x < side_; ++x) used[y * side + x] = used_[y * side_ + x];
    freeInRow[y] = side - (side_ - freeInRow_[y]);
  }
  side_ = side;
  used_ = std::move(used);
  freeInRow_ = std::move(freeInRow);
}

}  // namespace vt
