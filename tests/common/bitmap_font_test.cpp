// The project's one font (common/bitmap_font.h), and the HUD drawn with it.

#include "common/bitmap_font.h"

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

#include "common/checksum.h"
#include "gl/hud_text.h"

namespace vt {
namespace {

constexpr Glyph kBox = {0x1F, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1F, 0x00};
constexpr Rgba8 kRed{255, 0, 0, 255};

struct TestCanvas {
  int width, height;
  std::vector<uint8_t> rgba = std::vector<uint8_t>(size_t(width) * size_t(height) * 4, 0);
  RgbaCanvas view() { return {width, height, rgba}; }
  bool red(int x, int y) const {
    const uint8_t* p = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
    return p[0] == 255 && p[1] == 0 && p[2] == 0 && p[3] == 255;
  }
};

TEST(BitmapFont, DrawsAGlyphsPixelsAsScaledBlocksFromItsTopLeft) {
  TestCanvas canvas{20, 20};
  drawText(canvas.view(), 3, 2, "T", 2, kRed);
  // 'T': the top row five font pixels wide (x 3..12, y 2..3), the stem in the middle column down
  // to row 6 (x 7..8, y 14..15).
  for (int x = 3; x < 13; ++x) EXPECT_TRUE(canvas.red(x, 2) && canvas.red(x, 3)) << x;
  EXPECT_FALSE(canvas.red(13, 2));
  EXPECT_FALSE(canvas.red(2, 2));
  EXPECT_TRUE(canvas.red(7, 15) && canvas.red(8, 14));
  EXPECT_FALSE(canvas.red(6, 14));
  EXPECT_FALSE(canvas.red(7, 16));
}

TEST(BitmapFont, ClipsTextAtTheCanvasEdges) {
  TestCanvas canvas{8, 8};
  drawText(canvas.view(), -4, -4, "WW", 3, kRed);  // mostly outside, on every side
  size_t red = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) red += canvas.red(x, y);
  EXPECT_GT(red, 0u);
}

TEST(BitmapFont, MeasuresTextWithoutTheTrailingBlankColumn) {
  EXPECT_EQ(textWidth("", 2), 0);
  EXPECT_EQ(textWidth("x", 1), 5);
  EXPECT_EQ(textWidth("0.95", 3), (4 * 6 - 1) * 3);
}

TEST(BitmapFont, HasLowerCaseAndEveryCharacterAPlotNeeds) {
  for (const char c : std::string_view("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                       "0123456789.,-+%()/:=x*_"))
    EXPECT_NE(fontGlyph(c), kBox) << c;
  EXPECT_NE(fontGlyph('a'), fontGlyph('A'));
  EXPECT_EQ(fontGlyph(' '), Glyph{});
  EXPECT_EQ(fontGlyph('~'), kBox);  // unknown: a box
}

// The HUD's bytes for its characters, as the HUD's own font drew them before the font was shared
// (XXH3 of the RGBA rows).
TEST(HudText, DrawsTheSameBytesWithTheSharedFont) {
  const std::vector<std::string> lines = {"FRAME 12  3.4 MS  REC", "PAGES NEEDED 10  MISSING 2",
                                          "RESIDENT 5 / 64  8%", "ABCDEFGHIJKLMNOPQRSTUVWXYZ",
                                          "0123456789 .:%/-+()"};
  const HudImage one = renderHudText(lines, 1), two = renderHudText(lines, 2);
  EXPECT_EQ(one.width, 160u);
  EXPECT_EQ(one.height, 49u);
  EXPECT_EQ(checksum64(std::as_bytes(std::span(one.rgba))), 0xa59d42447f76cdd0u);
  EXPECT_EQ(two.width, 320u);
  EXPECT_EQ(two.height, 98u);
  EXPECT_EQ(checksum64(std::as_bytes(std::span(two.rgba))), 0xe6d212eb95a53f6fu);
}

}  // namespace
}  // namespace vt
