#pragma once
// The one built-in font of the project (the viewer's HUD, the evaluation's plots): 5 x 7 pixel
// glyphs in the style of the HD44780 character ROM, upper- and lower-case letters, digits and
// . , : ; - + * / = % ( ) [ ] < > _ ! ? # ' " & | and space; any other character is drawn as a
// box. Row 6 is the baseline; an eighth row below it holds the descenders of g j p q y , ; _.
// Each character advances 6 font pixels (one blank column between glyphs):
//
//   column   0 1 2 3 4 5
//   row 0    . # # # . .     'A' drawn at (x, y): its top-left font pixel covers
//   row 1    # . . . # .     [x, x + scale) x [y, y + scale), y counted downwards
//   ...
//   row 6    # . . . # .     <- baseline
//   row 7    . . . . . .     descenders only

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace vt {

// Font pixels: the glyph's width, its height above the baseline (capitals, digits), its rows
// with the descender row, and the distance from one character to the next.
inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphRows = 8, kGlyphAdvance = 6;

// Eight rows of five bits (the leftmost pixel in bit 4), top row first.
using Glyph = std::array<uint8_t, kGlyphRows>;
Glyph fontGlyph(char c);

struct Rgba8 {
  uint8_t r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Rgba8&) const = default;
};

// An RGBA8 image to draw into, rows top to bottom (rgba.size() == width * height * 4).
struct RgbaCanvas {
  int width = 0, height = 0;
  std::span<uint8_t> rgba;
};

// Draws `text` with its first glyph's top-left font pixel at pixel (x, y), each font pixel a
// scale x scale block of `colour` (written, not blended); pixels outside the canvas are skipped.
void drawText(RgbaCanvas canvas, int x, int y, std::string_view text, int scale, Rgba8 colour);

// The width in pixels from the first glyph's left edge to the last glyph's right edge (no
// trailing blank column): (6 n - 1) scale for n > 0 characters, 0 for none. The height is
// kGlyphHeight * scale down to the baseline, kGlyphRows * scale with the descenders.
int textWidth(std::string_view text, int scale);

}  // namespace vt
