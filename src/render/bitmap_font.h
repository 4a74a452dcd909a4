// A small hand-made 5x7 bitmap font (with 2 descender rows) for labels in pictures.
#pragma once

#include <array>
#include <cstdint>

namespace latfrac {

// Each glyph sits in a cell glyph_width wide and glyph_rows tall: rows 0-6 reach from
// the cap height to the baseline, rows 7-8 hold descenders (g, j, p, q, y, comma, _).
// Text advances glyph_advance columns per character (one blank column between glyphs).
inline constexpr int glyph_width = 5;
inline constexpr int glyph_rows = 9;
inline constexpr int glyph_cap_rows = 7;
inline constexpr int glyph_advance = 6;

struct Glyph {
  std::array<std::uint8_t, glyph_rows> rows{};  // bit 4 is the leftmost column

  bool ink(int column, int row) const { return (rows[row] >> (glyph_width - 1 - column)) & 1; }
};

// The glyph of `c`; characters the font lacks are drawn as an empty box.
const Glyph& glyph_for(char c);

}  // namespace latfrac
