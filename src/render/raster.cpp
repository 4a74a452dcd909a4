// The RGB canvas: clipped drawing primitives, bitmap text and PNG writing with libpng.
#include "raster.h"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "latfrac/base/atomic_write.h"
#include "bitmap_font.h"
#include "latfrac/base/error.h"

namespace latfrac {

std::vector<PixelOffset> disc_stencil(double radius) {
  std::vector<PixelOffset> stencil;
  const int reach = static_cast<int>(std::floor(radius));
  const double limit = radius * radius + 0.25;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx)
      if (dx * dx + dy * dy <= limit) stencil.push_back({dx, dy});
  if (stencil.empty()) stencil.push_back({0, 0});
  return stencil;
}

Canvas::Canvas(int width, int height, Rgb background)
    : width_(width), height_(height), rgb_(static_cast<std::size_t>(width) * height * 3) {
  if (width <= 0 || height <= 0)
    throw Error("Canvas: size " + std::to_string(width) + " x " + std::to_string(height) +
                " must be positive");
  fill_rect(0, 0, width, height, background);
}

Rgb Canvas::pixel(int x, int y) const {
  const std::uint8_t* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
  return {p[0], p[1], p[2]};
}

void Canvas::set(int x, int y, Rgb colour) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  std::uint8_t* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
  p[0] = colour.r;
  p[1] = colour.g;
  p[2] = colour.b;
}

void Canvas::fill_rect(int x0, int y0, int x1, int y1, Rgb colour) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width_);
  y1 = std::min(y1, height_);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) set(x, y, colour);
}

void Canvas::line(int x0, int y0, int x1, int y1, Rgb colour) {
  const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
  const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
  int error = dx + dy;
  while (true) {
    set(x0, y0, colour);
    if (x0 == x1 && y0 == y1) return;
    const int twice = 2 * error;
    if (twice >= dy) {
      error += dy;
      x0 += sx;
    }
    if (twice <= dx) {
      error += dx;
      y0 += sy;
    }
  }
}

void Canvas::stamp(int x, int y, const std::vector<PixelOffset>& stencil, Rgb colour) {
  for (const PixelOffset& offset : stencil) set(x + offset.dx, y + offset.dy, colour);
}

void Canvas::disc(double x, double y, double radius, Rgb colour) {
  const int x0 = static_cast<int>(std::ceil(x - radius)), x1 = static_cast<int>(std::floor(x + radius));
  const int y0 = static_cast<int>(std::ceil(y - radius)), y1 = static_cast<int>(std::floor(y + radius));
  bool painted = false;
  for (int py = y0; py <= y1; ++py)
    for (int px = x0; px <= x1; ++px)
      if ((px - x) * (px - x) + (py - y) * (py - y) <= radius * radius) {
        set(px, py, colour);
        painted = true;
      }
  if (!painted) set(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)), colour);
}

void Canvas::text(int x, int y, std::string_view text, int scale, Rgb colour) {
  for (char c : text) {
    const Glyph& glyph = glyph_for(c);
    for (int row = 0; row < glyph_rows; ++row)
      for (int column = 0; column < glyph_width; ++column)
        if (glyph.ink(column, row))
          fill_rect(x + column * scale, y + row * scale, x + (column + 1) * scale,
                    y + (row + 1) * scale, colour);
    x += glyph_advance * scale;
  }
}

void Canvas::vertical_text(int x, int y, std::string_view text, int scale, Rgb colour) {
  for (char c : text) {
    const Glyph& glyph = glyph_for(c);
    for (int row = 0; row < glyph_rows; ++row)
      for (int column = 0; column < glyph_width; ++column)
        if (glyph.ink(column, row))
          fill_rect(x + row * scale, y - (column + 1) * scale, x + (row + 1) * scale,
                    y - column * scale, colour);
    y -= glyph_advance * scale;
  }
}

int text_width(std::string_view text, int scale) {
  if (text.empty()) return 0;
  return (static_cast<int>(text.size()) * glyph_advance - 1) * scale;
}

int text_cap_height(int scale) { return glyph_cap_rows * scale; }

namespace {

// libpng reports errors by longjmp: keep the message and jump back to write_png_rows.
void on_png_error(png_structp png, png_const_charp message) {
  auto* buffer = static_cast<char*>(png_get_error_ptr(png));
  std::snprintf(buffer, 256, "libpng: %s", message);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// Encodes the image into `file`; on failure returns false with the reason in `message`
// (256 bytes). No C++ object with a destructor lives here, so longjmp is safe.
bool write_png_rows(std::FILE* file, int width, int height, const std::uint8_t* rgb,
                    char* message) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, message, on_png_error, on_png_warning);
  if (png == nullptr) {
    std::snprintf(message, 256, "png_create_write_struct failed");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(message, 256, "png_create_info_struct failed");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const std::size_t stride = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) png_write_row(png, rgb + y * stride);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void Canvas::write_png(const std::string& path) const {
  try {
    write_atomically(path, [&](const std::string& partial) {
      std::FILE* file = std::fopen(partial.c_str(), "wb");
      if (file == nullptr)
        throw Error(std::string("cannot create the file: ") + std::strerror(errno));
      char message[256] = "";
      bool written = write_png_rows(file, width_, height_, rgb_.data(), message);
      if (std::fclose(file) != 0 && written) {
        std::snprintf(message, sizeof message, "fclose: %s", std::strerror(errno));
        written = false;
      }
      if (!written) throw Error(message);
    });
  } catch (const Error& error) {
    throw Error("cannot write picture '" + path + "': " + error.what());
  }
}

}  // namespace latfrac
