// The builder's row ring: texels written read back while held, the background everywhere else,
// and memory only for the 256-column strips that held rows wrote into.

#include "build/row_ring.h"

#include <gtest/gtest.h>

#include <vector>

namespace vt {
namespace {

constexpr std::array<uint8_t, 4> kBackground = {7, 8, 9, 10};
constexpr uint64_t kStrip = RowRing::kStripTexels;

// Writes `count` texels of value `value` (both channels) at column x of the current row.
void put(RowRing& ring, uint64_t x, uint64_t count, uint8_t value) {
  ring.declare({x, x + count});
  const std::vector<uint8_t> texels(count * 2, value);
  ring.write(x, texels.data(), count);
}

TEST(RowRing, HeldRowsReadWhatWasWrittenAndTheBackgroundElsewhere) {
  RowRing ring(4 * kStrip, 2, 3, kBackground);
  ring.append(0);
  put(ring, kStrip - 2, 5, 100);  // across the boundary of strips 0 and 1
  ring.append(1);
  put(ring, 3 * kStrip + 1, 1, 101);
  for (uint64_t x = 0; x < 4 * kStrip; ++x) {
    const bool first = x >= kStrip - 2 && x < kStrip + 3;
    EXPECT_EQ(ring.texel(0, x)[0], first ? 100 : 7) << x;
    EXPECT_EQ(ring.texel(0, x)[1], first ? 100 : 8) << x;
    EXPECT_EQ(ring.texel(1, x)[0], x == 3 * kStrip + 1 ? 101 : 7) << x;
  }
  std::vector<uint8_t> row(8 * 2);
  ring.read(0, kStrip - 4, 8, row.data());
  EXPECT_EQ(row, (std::vector<uint8_t>{7, 8, 7, 8, 100, 100, 100, 100, 100, 100, 100, 100, 100,
                                       100, 7, 8}));
  EXPECT_THROW(ring.writable(0), std::logic_error);  // not declared by row 1
  EXPECT_THROW(ring.texel(2, 0), std::logic_error);  // not yet received
}

TEST(RowRing, AReplacedRowLeavesTheBackgroundAndItsStripsReturnToThePool) {
  RowRing ring(1024 * kStrip, 1, 2, kBackground);
  ring.append(0);
  put(ring, 10, 3, 50);
  const uint64_t oneStrip = ring.bytes();
  EXPECT_LT(oneStrip, ring.stripBytes() + 1024 * sizeof(uint32_t) + 1024);
  ring.append(1);
  ring.append(2);  // replaces row 0: its texels become the background again
  EXPECT_THROW(ring.texel(0, 10), std::logic_error);
  EXPECT_EQ(ring.texel(2, 10)[0], 7);
  EXPECT_EQ(ring.texel(1, 10)[0], 7);
  // Row 0's strip was retired; a write far away reuses it instead of making another.
  put(ring, 1000 * kStrip + 5, 1, 60);
  EXPECT_EQ(ring.texel(2, 1000 * kStrip + 5)[0], 60);
  EXPECT_EQ(ring.texel(2, 10)[0], 7);
  EXPECT_EQ(ring.bytes(), oneStrip);
}

TEST(RowRing, AStripStaysWhileAnyHeldRowWroteIntoIt) {
  RowRing ring(2 * kStrip, 1, 3, kBackground);
  ring.append(0);
  put(ring, 0, 1, 1);
  ring.append(1);
  ring.append(2);
  put(ring, 5, 1, 3);
  ring.append(3);  // row 0 leaves; row 2 still holds a texel in the strip
  ring.append(4);
  EXPECT_EQ(ring.texel(2, 5)[0], 3);
  EXPECT_EQ(ring.texel(2, 0)[0], 7);
  EXPECT_EQ(ring.texel(4, 5)[0], 7);
}

}  // namespace
}  // namespace vt
