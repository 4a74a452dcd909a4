// study.png: the errors of a convergence study against wall time, log-log, on the project's canvas.
//
// One point per finished run other than the reference, at (wall seconds, error): a filled
// disc for the broken-set difference, a hollow square for the first-break error, coloured
// by method and labelled with the increment. The reference is the dashed vertical line at
// its wall time. A log axis has no zero: an error of exactly 0 is drawn on the bottom edge,
// labelled 0 and set apart from the lowest decade (itself at least a tenth of a decade
// below the smallest positive error) by a gap and a break mark on the axis.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "latfrac/study/study.h"
#include "raster.h"
#include "render_axes.h"

namespace latfrac {
namespace {

constexpr Rgb paper{255, 255, 255}, ink{25, 25, 25}, grid_ink{228, 228, 228},
    reference_ink{110, 110, 110};
constexpr Rgb fixed_ink{31, 119, 180}, relaxation_ink{230, 120, 20};
constexpr int width = 1000, height = 700, scale = 2;
constexpr int marker = 5;     // disc radius and square half-side, pixels
constexpr int zero_gap = 36;  // between the lowest decade and the zero row, pixels

Rgb method_ink(const std::string& method) { return method == "fixed" ? fixed_ink : relaxation_ink; }

// The decades [low, high] (log10) that hold every positive value with a tenth of a decade
// to spare at each end; `fallback` when there is none.
std::pair<double, double> decade_range(const std::vector<double>& values,
                                       std::pair<double, double> fallback) {
  std::vector<double> positive;
  for (double v : values)
    if (v > 0 && std::isfinite(v)) positive.push_back(std::log10(v));
  if (positive.empty()) return fallback;
  const auto [lo, hi] = std::minmax_element(positive.begin(), positive.end());
  const double low = std::floor(*lo - 0.1), high = std::ceil(*hi + 0.1);
  return {low, std::max(high, low + 1)};
}

std::string decade_label(int k) {
  if (k >= 0 && k <= 3) return std::to_string(static_cast<int>(std::lround(std::pow(10.0, k))));
  if (k == -1) return "0.1";
  if (k == -2) return "0.01";
  return "1e" + std::to_string(k);
}

void hollow_square(Canvas& canvas, int x, int y, Rgb colour) {
  canvas.fill_rect(x - marker, y - marker, x + marker + 1, y - marker + 2, colour);
  canvas.fill_rect(x - marker, y + marker - 1, x + marker + 1, y + marker + 1, colour);
  canvas.fill_rect(x - marker, y - marker, x - marker + 2, y + marker + 1, colour);
  canvas.fill_rect(x + marker - 1, y - marker, x + marker + 1, y + marker + 1, colour);
}

struct LogAxes {
  AxisMap x, y;  // in log10 units
  int left, right, top, bottom;

  int px(double seconds) const { return x.pixel(std::log10(std::max(seconds, 1e-300))); }
  // An error of 0 lands on the bottom edge.
  int py(double error) const { return error > 0 ? y.pixel(std::log10(error)) : bottom; }
};

void draw_frame_and_ticks(Canvas& canvas, const LogAxes& axes) {
  const int cap = text_cap_height(scale);
  const int x_step = (axes.x.high - axes.x.low) > 8 ? 2 : 1,
            y_step = (axes.y.high - axes.y.low) > 8 ? 2 : 1;
  for (int k = static_cast<int>(axes.x.low); k <= static_cast<int>(axes.x.high); ++k) {
    const int x = axes.x.pixel(k);
    canvas.fill_rect(x, axes.top, x + 1, axes.bottom, grid_ink);
    canvas.fill_rect(x, axes.bottom, x + 2, axes.bottom + 8, ink);
    if ((k - static_cast<int>(axes.x.low)) % x_step == 0) {
      const std::string label = decade_label(k);
      canvas.text(x - text_width(label, scale) / 2, axes.bottom + 14, label, scale, ink);
    }
  }
  // Minor ticks at 2..9 x 10^k; on an axis of at most two decades, 2 and 5 are labelled.
  const bool label_minor = axes.x.high - axes.x.low <= 2;
  for (int k = static_cast<int>(axes.x.low); k < static_cast<int>(axes.x.high); ++k) {
    for (int mantissa = 2; mantissa <= 9; ++mantissa) {
      const int x = axes.x.pixel(k + std::log10(mantissa));
      canvas.fill_rect(x, axes.bottom, x + 1, axes.bottom + 5, ink);
      if (label_minor && (mantissa == 2 || mantissa == 5)) {
        char label[16];
        std::snprintf(label, sizeof label, k >= -3 && k <= 3 ? "%g" : "%.0e",
                      mantissa * std::pow(10.0, k));
        canvas.text(x - text_width(label, scale) / 2, axes.bottom + 14, label, scale, ink);
      }
    }
  }
  // The zero row on the bottom edge (the break mark above it is drawn after the frame).
  canvas.fill_rect(axes.left - 8, axes.bottom, axes.left, axes.bottom + 2, ink);
  canvas.text(axes.left - 14 - text_width("0", scale), axes.bottom - cap / 2, "0", scale, ink);
  for (int k = static_cast<int>(axes.y.low); k <= static_cast<int>(axes.y.high); ++k) {
    const int y = axes.y.pixel(k);
    canvas.fill_rect(axes.left, y, axes.right, y + 1, grid_ink);
    canvas.fill_rect(axes.left - 8, y, axes.left, y + 2, ink);
    if ((k - static_cast<int>(axes.y.low)) % y_step == 0) {
      const std::string label = decade_label(k);
      canvas.text(axes.left - 14 - text_width(label, scale), y - cap / 2, label, scale, ink);
    }
  }
  canvas.fill_rect(axes.left - 2, axes.top - 2, axes.right + 2, axes.top, ink);
  canvas.fill_rect(axes.left - 2, axes.bottom, axes.right + 2, axes.bottom + 2, ink);
  canvas.fill_rect(axes.left - 2, axes.top, axes.left, axes.bottom, ink);
  canvas.fill_rect(axes.right, axes.top, axes.right + 2, axes.bottom, ink);
  const int mark_y = axes.bottom - zero_gap / 2;
  canvas.fill_rect(axes.left - 8, mark_y - 5, axes.left + 8, mark_y + 5, paper);
  for (int offset : {-4, 3}) {
    canvas.line(axes.left - 9, mark_y + offset + 3, axes.left + 9, mark_y + offset - 3, ink);
    canvas.line(axes.left - 9, mark_y + offset + 4, axes.left + 9, mark_y + offset - 2, ink);
  }
}

// The legend, in the corner of the plot that hides the fewest points.
void draw_legend(Canvas& canvas, const LogAxes& axes, const std::vector<std::string>& methods,
                 const std::vector<PixelOffset>& points) {
  const int row = 26, advance = text_width("x", scale);
  std::vector<std::string> lines{"broken-set difference", "first-break error"};
  for (const std::string& m : methods) lines.push_back(m);
  int widest = 0;
  for (const std::string& line : lines) widest = std::max(widest, text_width(line, scale));
  const int box_width = widest + 3 * advance + 20,
            box_height = static_cast<int>(lines.size()) * row + 12;
  const int corners[4][2] = {{axes.right - box_width - 10, axes.top + 10},
                             {axes.left + 10, axes.top + 10},
                             {axes.right - box_width - 10, axes.bottom - box_height - 10},
                             {axes.left + 10, axes.bottom - box_height - 10}};
  int x0 = corners[0][0], y0 = corners[0][1];
  std::size_t fewest = points.size() + 1;
  for (const auto& corner : corners) {
    const std::size_t hidden =
        std::count_if(points.begin(), points.end(), [&](const PixelOffset& p) {
          return p.dx >= corner[0] - marker && p.dx <= corner[0] + box_width + marker &&
                 p.dy >= corner[1] - marker && p.dy <= corner[1] + box_height + marker;
        });
    if (hidden < fewest) {
      fewest = hidden;
      x0 = corner[0];
      y0 = corner[1];
    }
  }
  canvas.fill_rect(x0, y0, x0 + box_width, y0 + box_height, paper);
  canvas.line(x0, y0, x0 + box_width, y0, ink);
  canvas.line(x0, y0 + box_height, x0 + box_width, y0 + box_height, ink);
  canvas.line(x0, y0, x0, y0 + box_height, ink);
  canvas.line(x0 + box_width, y0, x0 + box_width, y0 + box_height, ink);
  const int symbol_x = x0 + 18, text_x = x0 + 36;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int centre = y0 + 6 + static_cast<int>(i) * row + row / 2;
    if (i == 0) canvas.stamp(symbol_x, centre, disc_stencil(marker), ink);
    if (i == 1) hollow_square(canvas, symbol_x, centre, ink);
    if (i >= 2)
      canvas.fill_rect(symbol_x - 8, centre - 3, symbol_x + 9, centre + 4, method_ink(lines[i]));
    canvas.text(text_x, centre - text_cap_height(scale) / 2, lines[i], scale, ink);
  }
}

}  // namespace

void write_study_plot(const StudyResult& study, const std::string& path) {
  const StudyRow* reference = nullptr;
  std::vector<const StudyRow*> runs;
  std::vector<double> times, errors;
  std::vector<std::string> methods;
  for (const StudyRow& row : study.rows) {
    if (row.status != RunStatus::ok) continue;
    times.push_back(row.wall_seconds);
    if (row.reference) {
      reference = &row;
      continue;
    }
    runs.push_back(&row);
    for (const auto& error : {row.broken_set_difference, row.first_break_error})
      if (error) errors.push_back(*error);
    if (std::find(methods.begin(), methods.end(), row.method) == methods.end())
      methods.push_back(row.method);
  }

  // 1. Layout: decades that hold every wall time and every positive error.
  Canvas canvas(width, height, paper);
  const auto [x_low, x_high] = decade_range(times, {-1, 1});
  const auto [y_low, y_high] = decade_range(errors, {-3, 0});
  LogAxes axes{{}, {}, 130, width - 30, 60, height - 130};
  axes.x = {x_low, x_high, axes.left, axes.right};
  axes.y = {y_low, y_high, axes.bottom - zero_gap, axes.top};
  draw_frame_and_ticks(canvas, axes);

  // 2. Titles and the note on zero errors.
  const std::string title = study.scene_name + ": error against wall time";
  canvas.text(std::max(10, (width - text_width(title, scale)) / 2), 20, title, scale, ink);
  const std::string x_title = "wall time (s)";
  canvas.text((axes.left + axes.right - text_width(x_title, scale)) / 2, axes.bottom + 44, x_title,
              scale, ink);
  const std::string y_title = "error (fraction)";
  canvas.vertical_text(14, (axes.top + axes.bottom + text_width(y_title, scale)) / 2, y_title,
                       scale, ink);
  const bool any_zero = std::any_of(errors.begin(), errors.end(), [](double e) { return e == 0; });
  if (any_zero) {
    canvas.text(axes.left, axes.bottom + 78, "points on the bottom edge (0): error exactly 0",
                scale, ink);
  }

  // 3. The reference's wall time, dashed.
  if (reference) {
    const int x = axes.px(reference->wall_seconds);
    for (int y = axes.top; y < axes.bottom; y += 12)
      canvas.fill_rect(x - 1, y, x + 1, std::min(y + 7, axes.bottom), reference_ink);
    const std::string label =
        "reference: " + reference->method +
        (reference->increment ? " ds=" + increment_text(*reference->increment) : "");
    const int label_x =
        x + 6 + text_width(label, scale) < axes.right ? x + 6 : x - 6 - text_width(label, scale);
    canvas.text(label_x, axes.bottom - 10 - text_cap_height(scale) - 24, label, scale,
                reference_ink);
  }

  // 4. The runs, then their increments: each label at the first place around its point
  //    where it covers no marker and no label placed before.
  struct Box {
    int x0, y0, x1, y1;
    bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  };
  struct Label {
    int x, y;
    std::string text;
    Rgb colour;
  };
  std::vector<PixelOffset> points;  // marker centres
  std::vector<Box> taken;           // marker and label boxes
  std::vector<Label> labels;
  for (const StudyRow* row : runs) {
    const Rgb colour = method_ink(row->method);
    const int x = axes.px(row->wall_seconds);
    std::optional<int> label_y;
    for (const bool disc : {false, true}) {
      const std::optional<double>& error =
          disc ? row->broken_set_difference : row->first_break_error;
      if (!error) continue;
      const int y = axes.py(*error);
      if (disc)
        canvas.stamp(x, y, disc_stencil(marker), colour);
      else
        hollow_square(canvas, x, y, colour);
      points.push_back({x, y});
      taken.push_back({x - marker, y - marker, x + marker + 1, y + marker + 1});
      label_y = y;
    }
    if (label_y && row->increment)
      labels.push_back({x, *label_y, increment_text(*row->increment), colour});
  }
  const Box plot_area{axes.left, axes.top, axes.right, axes.bottom};
  for (const Label& label : labels) {
    const int w = text_width(label.text, scale), h = text_cap_height(scale), d = marker + 3,
              x = label.x, y = label.y;
    // Right, then left of the point; above, below, beside; then further up or down.
    std::vector<Box> candidates;
    for (int level = 0; level < 4; ++level) {
      const int shift = level * (h + 4);
      for (const int left : {x + d, x - d - w}) {
        candidates.push_back({left, y - d - h - shift, left + w, y - d - shift});
        candidates.push_back({left, y + d + shift, left + w, y + d + h + shift});
        if (level == 0) candidates.push_back({left, y - h / 2, left + w, y + h - h / 2});
      }
    }
    auto inside = [&](const Box& box) {
      return box.x0 >= plot_area.x0 && box.x1 <= plot_area.x1 && box.y0 >= plot_area.y0 &&
             box.y1 <= plot_area.y1;
    };
    Box chosen = candidates[0];
    for (const Box& box : candidates) {
      if (inside(box) &&
          std::none_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(box); })) {
        chosen = box;
        break;
      }
    }
    taken.push_back(chosen);
    canvas.text(chosen.x0, chosen.y0, label.text, scale, label.colour);
  }
  draw_legend(canvas, axes, methods, points);
  canvas.write_png(path);
}

}  // namespace latfrac
