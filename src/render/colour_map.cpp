// The field colour map (viridis' nine anchor colours joined in CIELAB) and the mode colours.
#include "colour_map.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace latfrac {
namespace {

// viridis at t = 0, 1/8, ..., 1.
constexpr std::array<Colour, 9> anchors{{{0x44, 0x01, 0x54},
                                         {0x47, 0x2D, 0x7B},
                                         {0x3B, 0x52, 0x8B},
                                         {0x2C, 0x72, 0x8E},
                                         {0x21, 0x90, 0x8C},
                                         {0x27, 0xAD, 0x81},
                                         {0x5D, 0xC8, 0x63},
                                         {0xAA, 0xDC, 0x32},
                                         {0xFD, 0xE7, 0x25}}};

// D65 white point of CIE XYZ.
constexpr double white_x = 0.95047, white_y = 1.0, white_z = 1.08883;

double linear_of(std::uint8_t channel) {
  const double c = channel / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::uint8_t channel_of(double linear) {
  const double c = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(255 * std::clamp(c, 0.0, 1.0)));
}

double lab_f(double t) {
  constexpr double delta = 6.0 / 29;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29;
}

double lab_f_inverse(double t) {
  constexpr double delta = 6.0 / 29;
  return t > delta ? t * t * t : 3 * delta * delta * (t - 4.0 / 29);
}

Colour colour_of(const Lab& lab) {
  const double fy = (lab.l + 16) / 116, fx = fy + lab.a / 500, fz = fy - lab.b / 200;
  const double x = white_x * lab_f_inverse(fx), y = white_y * lab_f_inverse(fy),
               z = white_z * lab_f_inverse(fz);
  return {channel_of(3.2404542 * x - 1.5371385 * y - 0.4985314 * z),
          channel_of(-0.9692660 * x + 1.8760108 * y + 0.0415560 * z),
          channel_of(0.0556434 * x - 0.2040259 * y + 1.0572252 * z)};
}

}  // namespace

Lab lab_of(Colour colour) {
  const double r = linear_of(colour.r), g = linear_of(colour.g), b = linear_of(colour.b);
  const double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / white_x;
  const double y = (0.2126729 * r + 0.7151522 * g + 0.0721750 * b) / white_y;
  const double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / white_z;
  return {116 * lab_f(y) - 16, 500 * (lab_f(x) - lab_f(y)), 200 * (lab_f(y) - lab_f(z))};
}

Colour field_colour(double t) {
  if (std::isnan(t)) return no_value_colour;
  const double position = std::clamp(t, 0.0, 1.0) * (anchors.size() - 1);
  const std::size_t low = std::min(static_cast<std::size_t>(position), anchors.size() - 2);
  const double s = position - static_cast<double>(low);
  const Lab a = lab_of(anchors[low]), b = lab_of(anchors[low + 1]);
  return colour_of({a.l + (b.l - a.l) * s, a.a + (b.a - a.a) * s, a.b + (b.b - a.b) * s});
}

Colour mode_colour(std::int8_t mode) {
  switch (mode) {
    case 0: return tensile_colour;
    case 1: return shear_colour;
    case 2: return precut_colour;
    default: return unknown_mode_colour;
  }
}

}  // namespace latfrac
