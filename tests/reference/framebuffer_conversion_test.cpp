// The framebuffer conversion family (render/arithmetic.h, ColourConversion;
// reference/framebuffer_conversion.h) on values worked out by hand.

#include "reference/framebuffer_conversion.h"

#include <gtest/gtest.h>

namespace vt::reference {
namespace {

constexpr ColourConversion kQuantized12{ColourConversionRule::kQuantized, 12, 2047};

TEST(FramebufferConversion, QuantizedTruncatesToItsBitsThenScalesWithItsBias) {
  // 0.5: nearest even of 127.5 is 128; quantized, k = 2048 and (255 2048 + 2047) >> 12 =
  // 524287 >> 12 = 127.
  EXPECT_EQ(toUnorm8(0.5f), 128);
  EXPECT_EQ(toUnorm8(0.5f, kQuantized12), 127);
  // 1 / 255 (a float a little above it): k = floor(4096 / 255) = 16, (4080 + 2047) >> 12 = 1.
  EXPECT_EQ(toUnorm8(1.0f / 255.0f, kQuantized12), 1);
  // The ends, and what lies beyond them or is no number.
  EXPECT_EQ(toUnorm8(1.0f, kQuantized12), 255);
  EXPECT_EQ(toUnorm8(0.0f, kQuantized12), 0);
  EXPECT_EQ(toUnorm8(2.0f, kQuantized12), 255);
  EXPECT_EQ(toUnorm8(-1.0f, kQuantized12), 0);
  EXPECT_EQ(toUnorm8(std::nanf(""), kQuantized12), 0);
  // Another bias, another member: without it 0.5 gives (255 2048) >> 12 = 127 too, and
  // 254.9 / 255 gives k = 4094, (1043970 + 0) >> 12 = 254 where the bias of 2047 gives 255.
  const ColourConversion unbiased{ColourConversionRule::kQuantized, 12, 0};
  EXPECT_EQ(toUnorm8(254.9f / 255.0f, unbiased), 254);
  EXPECT_EQ(toUnorm8(254.9f / 255.0f, kQuantized12), 255);
  // The nearest member is toUnorm8's rounding, whatever bits and bias say.
  EXPECT_EQ(toUnorm8(0.5f, ColourConversion{}), 128);
}

}  // namespace
}  // namespace vt::reference
