// The Cairo surface of one picture file, its checked drawing calls and its atomic write.
#include "canvas.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "latfrac/base/atomic_write.h"
#include "latfrac/base/error.h"

namespace latfrac {
namespace {

// DejaVu Sans' cap height as a fraction of the font size (1493 / 2048 font units).
constexpr double cap_height = 0.729;

double channel(std::uint8_t value) { return value / 255.0; }

}  // namespace

PictureFormat picture_format_of(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".png") return PictureFormat::png;
  if (extension == ".svg") return PictureFormat::svg;
  if (extension == ".pdf") return PictureFormat::pdf;
  throw InputError("'" + path + "': unsupported picture format '" + extension +
                   "'; allowed: a file name ending in .png, .svg or .pdf");
}

Colour mix(Colour a, Colour b, double t) {
  auto blend = [t](std::uint8_t x, std::uint8_t y) {
    return static_cast<std::uint8_t>(std::lround(x + (y - x) * std::clamp(t, 0.0, 1.0)));
  };
  return {blend(a.r, b.r), blend(a.g, b.g), blend(a.b, b.b)};
}

Canvas::Canvas(PictureFormat format, const std::string& path, int width, int height)
    : format_(format), path_(path), width_(width), height_(height) {
  switch (format) {
    case PictureFormat::png:
      surface_ = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
      break;
    case PictureFormat::svg:
      surface_ = cairo_svg_surface_create(path.c_str(), width, height);
      break;
    case PictureFormat::pdf:
      surface_ = cairo_pdf_surface_create(path.c_str(), width, height);
      break;
  }
  if (const cairo_status_t status = cairo_surface_status(surface_); status != CAIRO_STATUS_SUCCESS)
    throw Error("cairo surface for '" + path + "' (" + std::to_string(width) + " x " +
                std::to_string(height) + "): " + cairo_status_to_string(status));
  cr_ = cairo_create(surface_);
  check("cairo_create");
  cairo_select_font_face(cr_, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  check("cairo_select_font_face(DejaVu Sans)");
  cairo_set_source_rgb(cr_, 1, 1, 1);
  cairo_paint(cr_);
  check("cairo_paint");
}

Canvas::~Canvas() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
}

void Canvas::check(const char* call) {
  const cairo_status_t status = cairo_status(cr_);
  if (status != CAIRO_STATUS_SUCCESS)
    throw Error(std::string(call) + " failed drawing '" + path_ + "': " +
                cairo_status_to_string(status));
}

void Canvas::colour(Colour c, double alpha) {
  cairo_set_source_rgba(cr_, channel(c.r), channel(c.g), channel(c.b), alpha);
  check("cairo_set_source_rgba");
}

void Canvas::line_width(double width) {
  cairo_set_line_width(cr_, width);
  check("cairo_set_line_width");
}

void Canvas::dash(double on, double off) {
  const double pattern[2] = {on, off};
  cairo_set_dash(cr_, pattern, on > 0 ? 2 : 0, 0);
  check("cairo_set_dash");
}

void Canvas::round_caps() {
  cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
  check("cairo_set_line_cap");
}

void Canvas::move_to(double x, double y) {
  cairo_move_to(cr_, x, y);
  check("cairo_move_to");
}

void Canvas::line_to(double x, double y) {
  cairo_line_to(cr_, x, y);
  check("cairo_line_to");
}

void Canvas::rectangle(double x, double y, double width, double height) {
  cairo_rectangle(cr_, x, y, width, height);
  check("cairo_rectangle");
}

void Canvas::circle(double x, double y, double radius) {
  cairo_new_sub_path(cr_);
  cairo_arc(cr_, x, y, radius, 0, 2 * std::numbers::pi);
  check("cairo_arc");
}

void Canvas::close_path() {
  cairo_close_path(cr_);
  check("cairo_close_path");
}

void Canvas::stroke() {
  cairo_stroke(cr_);
  check("cairo_stroke");
}

void Canvas::fill() {
  cairo_fill(cr_);
  check("cairo_fill");
}

void Canvas::fill_preserve() {
  cairo_fill_preserve(cr_);
  check("cairo_fill_preserve");
}

void Canvas::fill_gradient(double x, double y, double width, double height,
                           const std::vector<Colour>& colours) {
  cairo_pattern_t* pattern = cairo_pattern_create_linear(0, y + height, 0, y);
  for (std::size_t i = 0; i < colours.size(); ++i)
    cairo_pattern_add_color_stop_rgb(pattern, colours.size() > 1 ? i / (colours.size() - 1.0) : 0,
                                     channel(colours[i].r), channel(colours[i].g),
                                     channel(colours[i].b));
  const cairo_status_t status = cairo_pattern_status(pattern);
  if (status == CAIRO_STATUS_SUCCESS) {
    cairo_rectangle(cr_, x, y, width, height);
    cairo_set_source(cr_, pattern);
    cairo_fill(cr_);
  }
  cairo_pattern_destroy(pattern);
  if (status != CAIRO_STATUS_SUCCESS)
    throw Error("cairo_pattern_create_linear failed drawing '" + path_ + "': " +
                cairo_status_to_string(status));
  check("cairo_fill (gradient)");
}

void Canvas::clip_rectangle(double x, double y, double width, double height) {
  cairo_rectangle(cr_, x, y, width, height);
  cairo_clip(cr_);
  check("cairo_clip");
}

void Canvas::reset_clip() {
  cairo_reset_clip(cr_);
  check("cairo_reset_clip");
}

void Canvas::font_size(double size) {
  font_size_ = size;
  cairo_set_font_size(cr_, size);
  check("cairo_set_font_size");
}

double Canvas::text_width(std::string_view text) {
  const std::string copy(text);
  cairo_text_extents_t extents;
  cairo_text_extents(cr_, copy.c_str(), &extents);
  check("cairo_text_extents");
  return extents.x_advance;
}

void Canvas::text(double x, double y, std::string_view text, Align h, Align v, bool upright) {
  const double width = text_width(text);
  const double along = h == Align::start ? 0 : h == Align::centre ? -width / 2 : -width;
  const double cap = cap_height * font_size_;
  const double across = v == Align::start ? cap : v == Align::centre ? cap / 2 : 0;
  cairo_save(cr_);
  cairo_translate(cr_, x, y);
  if (upright) cairo_rotate(cr_, -std::numbers::pi / 2);
  cairo_move_to(cr_, along, across);
  const std::string copy(text);
  cairo_show_text(cr_, copy.c_str());
  cairo_restore(cr_);
  check("cairo_show_text");
}

void Canvas::finish() {
  if (format_ == PictureFormat::png) {
    cairo_surface_flush(surface_);
    const cairo_status_t status = cairo_surface_write_to_png(surface_, path_.c_str());
    if (status != CAIRO_STATUS_SUCCESS)
      throw Error("cairo_surface_write_to_png('" + path_ + "'): " + cairo_status_to_string(status));
    return;
  }
  cairo_surface_finish(surface_);
  if (const cairo_status_t status = cairo_surface_status(surface_); status != CAIRO_STATUS_SUCCESS)
    throw Error("cairo_surface_finish('" + path_ + "'): " + cairo_status_to_string(status));
}

void draw_picture_file(const std::string& path, int width, int height,
                       const std::function<void(Canvas&)>& draw) {
  const PictureFormat format = picture_format_of(path);
  // The picture's folder is made when missing, as `latfrac run -o` makes its own.
  make_directory(std::filesystem::path(path).parent_path());
  write_atomically(path, [&](const std::string& partial) {
    Canvas canvas(format, partial, width, height);
    draw(canvas);
    canvas.finish();
  });
}

}  // namespace latfrac
