// Plot axes: nice linear steps, log decades, the frame, ticks, labels and titles, with Cairo.
#include "plot_axes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "colour_map.h"

namespace latfrac {
namespace {

constexpr Colour grid_colour{225, 225, 225};

std::string fixed_label(double value, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string label = text;
  if (label[0] == '-' && label.find_first_not_of("-0.") == std::string::npos) label.erase(0, 1);
  return label;
}

std::string decade_label(int k) {
  if (k >= 0 && k <= 3) return std::to_string(static_cast<int>(std::lround(std::pow(10.0, k))));
  if (k == -1) return "0.1";
  if (k == -2) return "0.01";
  return "1e" + std::to_string(k);
}

}  // namespace

double Axis::position(double value) const {
  const double at = log ? std::log10(value) : value;
  return pixel_low + (at - low) / (high - low) * (pixel_high - pixel_low);
}

double Axis::pixels_per_unit() const { return std::abs(pixel_high - pixel_low) / (high - low); }

double nice_step_at_least(double value) {
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  for (double mantissa : {1.0, 2.0, 5.0})
    if (mantissa * decade >= value * (1 - 1e-9)) return mantissa * decade;
  return 10 * decade;
}

std::vector<Tick> linear_ticks(Canvas& canvas, const Axis& axis, double label_unit,
                               bool labels_side_by_side) {
  const double em = canvas.text_width("0");
  double step = nice_step_at_least((axis.high - axis.low) / 12);
  while (true) {
    std::vector<Tick> ticks;
    double widest = 0;
    for (double k = std::ceil(axis.low / step - 1e-9); k * step <= axis.high + 1e-9 * step; k += 1) {
      ticks.push_back({k * step, fixed_label(k * step / label_unit, step / label_unit)});
      widest = std::max(widest, canvas.text_width(ticks.back().label));
    }
    const double needed = labels_side_by_side ? widest + 2.5 * em : 3 * em;
    if (step * axis.pixels_per_unit() >= needed || ticks.size() <= 2) return ticks;
    step = nice_step_at_least(step * 1.5);
  }
}

std::vector<Tick> log_ticks(const Axis& axis) {
  std::vector<Tick> ticks;
  const int first = static_cast<int>(std::floor(axis.low)), last = static_cast<int>(std::ceil(axis.high));
  const bool label_minor = axis.high - axis.low <= 2;
  const int label_every = axis.high - axis.low > 8 ? 2 : 1;
  for (int k = first; k <= last; ++k) {
    for (int mantissa = 1; mantissa <= 9; ++mantissa) {
      const double at = k + std::log10(mantissa);
      if (at < axis.low - 1e-9 || at > axis.high + 1e-9) continue;
      std::string label;
      if (mantissa == 1 && (k - first) % label_every == 0) label = decade_label(k);
      if (label_minor && (mantissa == 2 || mantissa == 5)) {
        char text[16];
        std::snprintf(text, sizeof text, k >= -3 && k <= 3 ? "%g" : "%.0e", mantissa * std::pow(10.0, k));
        label = text;
      }
      ticks.push_back({std::pow(10.0, at), label});
    }
  }
  return ticks;
}

void draw_axes(Canvas& canvas, const Frame& frame, const Axis& h, const std::vector<Tick>& h_ticks,
               const Axis& v, const std::vector<Tick>& v_ticks, const AxisTitles& titles,
               bool grid) {
  const double em = canvas.text_width("0");
  const double major = 0.6 * em, minor = 0.35 * em, line = std::max(1.0, em / 10);
  if (grid) {
    canvas.colour(grid_colour);
    canvas.line_width(line);
    for (const Tick& tick : h_ticks)
      if (!tick.label.empty()) canvas.segment(h.position(tick.value), frame.top, h.position(tick.value), frame.bottom);
    for (const Tick& tick : v_ticks)
      if (!tick.label.empty()) canvas.segment(frame.left, v.position(tick.value), frame.right, v.position(tick.value));
    canvas.stroke();
  }
  canvas.colour(ink_colour);
  canvas.line_width(line);
  canvas.rectangle(frame.left, frame.top, frame.right - frame.left, frame.bottom - frame.top);
  for (const Tick& tick : h_ticks) {
    const double x = h.position(tick.value);
    canvas.segment(x, frame.bottom, x, frame.bottom + (tick.label.empty() ? minor : major));
  }
  for (const Tick& tick : v_ticks) {
    const double y = v.position(tick.value);
    canvas.segment(frame.left, y, frame.left - (tick.label.empty() ? minor : major), y);
  }
  canvas.stroke();

  double widest = 0;
  for (const Tick& tick : h_ticks)
    if (!tick.label.empty())
      canvas.text(h.position(tick.value), frame.bottom + major + 0.5 * em, tick.label, Align::centre,
                  Align::start);
  for (const Tick& tick : v_ticks) {
    if (tick.label.empty()) continue;
    canvas.text(frame.left - major - 0.5 * em, v.position(tick.value), tick.label, Align::end,
                Align::centre);
    widest = std::max(widest, canvas.text_width(tick.label));
  }
  if (!titles.h.empty())
    canvas.text(0.5 * (frame.left + frame.right), frame.bottom + major + 2.4 * em, titles.h,
                Align::centre, Align::start);
  if (!titles.v.empty())
    canvas.text(frame.left - major - widest - 1.4 * em, 0.5 * (frame.top + frame.bottom), titles.v,
                Align::centre, Align::end, true);
}

}  // namespace latfrac
