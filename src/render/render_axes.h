// Layout of a cross-section picture (margins, frame, data-to-pixel maps) and its axes.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "raster.h"

namespace latfrac {

// The part of the x-z plane the frame shows, m.
struct SectionWindow {
  double x_min = 0, x_max = 1, z_min = 0, z_max = 1;
};

// Maps a coordinate (m) linearly onto pixels: `low` lands on pixel_at_low, `high` on
// pixel_at_high (smaller than pixel_at_low for z, which points up).
struct AxisMap {
  double low = 0, high = 1;
  int pixel_at_low = 0, pixel_at_high = 1;

  // Where value lands, in pixels; pixel i covers [i - 0.5, i + 0.5).
  double position(double value) const {
    return pixel_at_low + (value - low) / (high - low) * (pixel_at_high - pixel_at_low);
  }
  int pixel(double value) const { return static_cast<int>(std::lround(position(value))); }
  double pixels_per_unit() const { return std::abs(pixel_at_high - pixel_at_low) / (high - low); }
};

struct SectionLayout {
  int width = 0, height = 0;  // of the whole picture, pixels
  int text_scale = 1;         // font pixels are text_scale x text_scale blocks
  AxisMap x, z;               // the frame's inner edges are x.pixel_at_low .. z.pixel_at_low
};

// Picks margins for the labels and a plot area with equal x and z scales (within limits
// for very flat or very tall sections) so the picture is `width` pixels wide.
SectionLayout layout_section(const SectionWindow& window, int width);

struct Tick {
  double value = 0;   // m
  std::string label;  // km
};

// Ticks at multiples of a 'nice' step (1, 2 or 5 x 10^k m), the smallest step whose
// labels do not crowd each other.
std::vector<Tick> choose_ticks(const AxisMap& axis, bool labels_side_by_side, int text_scale);

// The frame, ticks, tick labels, axis titles and the title above the frame.
void draw_axes(Canvas& canvas, const SectionLayout& layout, const std::string& title);

}  // namespace latfrac
