// The colours of the pictures: a perceptually uniform map for fields, and the break modes'.
#pragma once

#include <cstdint>

#include "canvas.h"

namespace latfrac {

// The colour of t in [0, 1] (clamped; NaN gives no_value_colour) on a viridis-like map: dark
// blue-violet through teal and green to yellow, its lightness rising evenly. The map passes
// through nine colours of viridis (t = 0, 1/8, ..., 1) and is interpolated between them in
// CIELAB, so equal steps in t are about equal steps in perceived colour.
Colour field_colour(double t);
inline constexpr Colour no_value_colour{200, 200, 200};

// CIE 1976 L* a* b* (D65) of an sRGB colour.
struct Lab {
  double l = 0, a = 0, b = 0;
};
Lab lab_of(Colour colour);

// The cracks: a segment per broken bond in the colour of its mode (criteria/criterion.h's
// BreakMode: 0 tensile, 1 shear, 2 pre-cut). Red, blue and black are told apart by readers
// with red-green colour blindness, and none of them is on the field map.
Colour mode_colour(std::int8_t mode);
inline constexpr Colour tensile_colour{215, 25, 28};
inline constexpr Colour shear_colour{33, 102, 172};
inline constexpr Colour precut_colour{20, 20, 20};
inline constexpr Colour unknown_mode_colour{140, 140, 140};  // a broken bond without an event

// The lattice under the cracks, the paper's particles, and the red of "touches a broken bond".
inline constexpr Colour lattice_colour{205, 205, 205};
inline constexpr Colour particle_colour{90, 90, 90};
inline constexpr Colour broken_particle_colour{220, 20, 20};
inline constexpr Colour ink_colour{25, 25, 25};
inline constexpr Colour paper_colour{255, 255, 255};

}  // namespace latfrac
