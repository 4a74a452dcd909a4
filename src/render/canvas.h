// One picture file drawn with Cairo: PNG, SVG or PDF by extension, every call checked.
//
// Coordinates are pixels (points for SVG and PDF) from the top-left corner, y down. Each
// wrapper checks the context's status after its Cairo call and throws latfrac::Error
// naming that call, so a failure is reported where it happened, not at the end.
#pragma once

#include <cairo.h>

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "latfrac/render/render.h"

namespace latfrac {

struct Colour {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Colour&) const = default;
};

// a + (b - a) t, per channel.
Colour mix(Colour a, Colour b, double t);

enum class Align { start, centre, end };

class Canvas final {
 public:
  Canvas(PictureFormat format, const std::string& path, int width, int height);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }

  void colour(Colour c, double alpha = 1);
  void line_width(double width);
  void dash(double on, double off);  // on = 0: solid
  void round_caps();

  void move_to(double x, double y);
  void line_to(double x, double y);
  void segment(double x0, double y0, double x1, double y1) { move_to(x0, y0), line_to(x1, y1); }
  void rectangle(double x, double y, double width, double height);
  void circle(double x, double y, double radius);
  void close_path();
  void stroke();
  void fill();
  void fill_preserve();
  // The rectangle filled with `colours` spread evenly from its bottom edge to its top.
  void fill_gradient(double x, double y, double width, double height,
                     const std::vector<Colour>& colours);
  void clip_rectangle(double x, double y, double width, double height);
  void reset_clip();

  // Text in DejaVu Sans of `size` pixels. (x, y) is the anchor: `h` aligns the text's
  // advance, `v` its cap height (start: top at y, centre: middle at y, end: baseline at y).
  // `upright` turns the text a quarter turn anticlockwise, reading upwards.
  void font_size(double size);
  double text_width(std::string_view text);
  void text(double x, double y, std::string_view text, Align h, Align v, bool upright = false);

  // Writes the file (PNG) or ends it (SVG, PDF); throws Error naming the failed call.
  void finish();

 private:
  void check(const char* call);

  PictureFormat format_;
  std::string path_;
  int width_, height_;
  double font_size_ = 12;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
};

// Draws a picture of width x height into `path`, written under a temporary name and
// renamed when complete: a failed drawing or write leaves no file at `path`.
void draw_picture_file(const std::string& path, int width, int height,
                       const std::function<void(Canvas&)>& draw);

}  // namespace latfrac
