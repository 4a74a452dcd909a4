// Axes of a plot: linear (labelled in km) or logarithmic, their ticks, the frame and titles.
#pragma once

#include <string>
#include <vector>

#include "canvas.h"

namespace latfrac {

// Maps data values onto pixels: `low` lands on pixel_low, `high` on pixel_high (smaller
// than pixel_low on a vertical axis). A log axis holds log10 of the data in low and high.
struct Axis {
  double low = 0, high = 1;
  double pixel_low = 0, pixel_high = 1;
  bool log = false;

  double position(double value) const;  // value in data units, never log10
  double pixels_per_unit() const;       // per data unit (per decade on a log axis)
};

struct Tick {
  double value = 0;   // data units
  std::string label;  // "" for an unlabelled (minor) tick
};

// Ticks at multiples of a nice step (1, 2 or 5 x 10^k data units), labelled in data units
// divided by `label_unit` (1000: metres labelled in km): the smallest step whose labels do
// not crowd each other in the canvas' current font (side by side on a horizontal axis).
std::vector<Tick> linear_ticks(Canvas& canvas, const Axis& axis, double label_unit,
                               bool labels_side_by_side);

// Decades labelled (0.01, 0.1, 1, 10, 100, else 1e-5); 2..9 x 10^k as minor ticks, 2 and
// 5 labelled on an axis of at most two decades.
std::vector<Tick> log_ticks(const Axis& axis);

struct Frame {
  double left = 0, top = 0, right = 1, bottom = 1;
};

struct AxisTitles {
  std::string h, v;
};

// The frame, ticks pointing out, tick labels and axis titles; `grid` adds light lines at
// the labelled ticks. The canvas' font size is the labels'.
void draw_axes(Canvas& canvas, const Frame& frame, const Axis& h, const std::vector<Tick>& h_ticks,
               const Axis& v, const std::vector<Tick>& v_ticks, const AxisTitles& titles,
               bool grid = false);

// The smallest of 1, 2 or 5 x 10^k that is at least `value` (> 0).
double nice_step_at_least(double value);

}  // namespace latfrac
