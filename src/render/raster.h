// A tiny RGB canvas for pictures: rectangles, lines, dots, bitmap text, PNG output.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace latfrac {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

struct PixelOffset {
  int dx = 0, dy = 0;
};

// The pixel offsets of a filled disc of `radius` pixels around its centre; a radius
// below 1 gives the centre pixel alone.
std::vector<PixelOffset> disc_stencil(double radius);

// Pixels are addressed (x, y) with x to the right and y down from the top-left corner;
// everything drawn outside the canvas is clipped.
class Canvas final {
 public:
  Canvas(int width, int height, Rgb background);

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb pixel(int x, int y) const;

  void set(int x, int y, Rgb colour);
  // The rectangle [x0, x1) x [y0, y1).
  void fill_rect(int x0, int y0, int x1, int y1, Rgb colour);
  void line(int x0, int y0, int x1, int y1, Rgb colour);
  void stamp(int x, int y, const std::vector<PixelOffset>& stencil, Rgb colour);
  // Every pixel whose centre lies within `radius` of (x, y), in pixels (pixel i's centre
  // is at i); the nearest pixel alone when no centre does.
  void disc(double x, double y, double radius, Rgb colour);

  // Text in the bitmap font, each font pixel drawn as a scale x scale block. Horizontal
  // text has the top-left corner of its first character cell at (x, y); vertical text
  // reads upwards, with the bottom-left corner of its first cell at (x, y).
  void text(int x, int y, std::string_view text, int scale, Rgb colour);
  void vertical_text(int x, int y, std::string_view text, int scale, Rgb colour);

  // Writes "<path>.partial" and renames it to `path` once complete; throws
  // latfrac::Error naming the failed call and leaves no file behind on failure.
  void write_png(const std::string& path) const;

 private:
  int width_;
  int height_;
  std::vector<std::uint8_t> rgb_;  // row-major, 3 bytes a pixel
};

// Width in pixels of `text` drawn at `scale` (without the trailing blank column).
int text_width(std::string_view text, int scale);
// Height in pixels of a character cell's cap height (ascender to baseline) at `scale`.
int text_cap_height(int scale);

}  // namespace latfrac
