// study.png: a convergence study in two log-log panels, drawn with Cairo (src/render/canvas.h).
//
// Left: error against wall time. One series per method: a filled disc per run for the
// broken-set difference (joined by a line in the order of falling increment), a hollow
// square for the first-break error (joined by a dashed line), each disc labelled with its
// increment. The reference is the dashed vertical line at its wall time. A log axis has no
// zero: an error of exactly 0 is drawn on the bottom edge, labelled 0 and set apart from
// the lowest decade by a gap. Right: wall time against increment, one series per method,
// the reference's wall time a dashed horizontal line.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "canvas.h"
#include "colour_map.h"
#include "latfrac/study/study.h"
#include "plot_axes.h"

namespace latfrac {
namespace {

constexpr int width = 1400, height = 640;
constexpr double font = 15, marker = 5;
constexpr Colour reference_colour{110, 110, 110};

Colour method_colour(const std::string& method) {
  return method == "fixed" ? Colour{31, 119, 180} : Colour{230, 120, 20};
}

// The decades [low, high] (log10) that hold every positive value with a tenth of a decade
// to spare at each end; `fallback` when there is none.
std::pair<double, double> decade_range(const std::vector<double>& values,
                                       std::pair<double, double> fallback) {
  std::vector<double> logs;
  for (double v : values)
    if (v > 0 && std::isfinite(v)) logs.push_back(std::log10(v));
  if (logs.empty()) return fallback;
  const auto [lo, hi] = std::minmax_element(logs.begin(), logs.end());
  const double low = std::floor(*lo - 0.1), high = std::ceil(*hi + 0.1);
  return {low, std::max(high, low + 1)};
}

struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

void marker_at(Canvas& canvas, double x, double y, bool disc, Colour colour) {
  canvas.colour(colour);
  if (disc) {
    canvas.circle(x, y, marker);
    canvas.fill();
  } else {
    canvas.line_width(1.6);
    canvas.rectangle(x - marker, y - marker, 2 * marker, 2 * marker);
    canvas.stroke();
  }
}

// Lines through points in order, then the markers on top.
void series(Canvas& canvas, const std::vector<std::pair<double, double>>& points, bool disc,
            Colour colour) {
  canvas.colour(colour);
  canvas.line_width(1.2);
  canvas.dash(disc ? 0 : 5, 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    i == 0 ? canvas.move_to(points[i].first, points[i].second)
           : canvas.line_to(points[i].first, points[i].second);
  if (points.size() > 1) canvas.stroke();
  canvas.dash(0, 0);
  for (const auto& [x, y] : points) marker_at(canvas, x, y, disc, colour);
}

struct Runs {
  const StudyRow* reference = nullptr;
  std::map<std::string, std::vector<const StudyRow*>> by_method;  // falling increment
  std::vector<double> times, errors, increments;
};

Runs gather(const StudyResult& study) {
  Runs runs;
  for (const StudyRow& row : study.rows) {
    if (row.status != RunStatus::ok) continue;
    runs.times.push_back(row.wall_seconds);
    if (row.reference) {
      runs.reference = &row;
      continue;
    }
    runs.by_method[row.method].push_back(&row);
    for (const auto& error : {row.broken_set_difference, row.first_break_error})
      if (error) runs.errors.push_back(*error);
    if (row.increment) runs.increments.push_back(*row.increment);
  }
  for (auto& [method, rows] : runs.by_method)
    std::stable_sort(rows.begin(), rows.end(), [](const StudyRow* a, const StudyRow* b) {
      return a->increment.value_or(0) > b->increment.value_or(0);
    });
  return runs;
}

void error_panel(Canvas& canvas, const Runs& runs, const Frame& frame) {
  const double zero_gap = 2.4 * font;
  const auto [x_low, x_high] = decade_range(runs.times, {-1, 1});
  const auto [y_low, y_high] = decade_range(runs.errors, {-3, 0});
  const Axis x{x_low, x_high, frame.left, frame.right, true};
  const Axis y{y_low, y_high, frame.bottom - zero_gap, frame.top, true};
  draw_axes(canvas, frame, x, log_ticks(x), y, log_ticks(y), {"wall time (s)", "error (fraction)"},
            true);
  canvas.colour(ink_colour);
  canvas.text(frame.left - 0.6 * font - 0.5 * font, frame.bottom, "0", Align::end, Align::centre);
  canvas.colour(paper_colour);  // a break in the axis between the zero row and the decades
  canvas.rectangle(frame.left - 0.6 * font, frame.bottom - 0.5 * zero_gap - 3, 1.2 * font, 6);
  canvas.fill();

  auto px = [&](double seconds) { return x.position(std::max(seconds, 1e-300)); };
  auto py = [&](double error) { return error > 0 ? y.position(error) : frame.bottom; };
  if (runs.reference) {
    const double at = px(runs.reference->wall_seconds);
    canvas.colour(reference_colour);
    canvas.line_width(1.5);
    canvas.dash(6, 4);
    canvas.segment(at, frame.top, at, frame.bottom);
    canvas.stroke();
    canvas.dash(0, 0);
    canvas.text(at + 0.4 * font, frame.top + 0.8 * font, "reference", Align::start, Align::centre);
  }
  std::vector<Box> taken;
  for (const auto& [method, rows] : runs.by_method) {
    for (const bool disc : {false, true}) {
      std::vector<std::pair<double, double>> points;
      for (const StudyRow* row : rows) {
        const std::optional<double>& error = disc ? row->broken_set_difference : row->first_break_error;
        if (!error) continue;
        points.push_back({px(row->wall_seconds), py(*error)});
        taken.push_back({points.back().first - marker, points.back().second - marker,
                         points.back().first + marker, points.back().second + marker});
      }
      series(canvas, points, disc, method_colour(method));
    }
  }
  // Each disc's increment at the first place beside it that covers no marker or label.
  canvas.font_size(0.85 * font);
  for (const auto& [method, rows] : runs.by_method)
    for (const StudyRow* row : rows) {
      if (!row->increment || !row->broken_set_difference) continue;
      const std::string text = increment_text(*row->increment);
      const double w = canvas.text_width(text), h = 0.85 * font, d = marker + 3;
      const double cx = px(row->wall_seconds), cy = py(*row->broken_set_difference);
      Box chosen{cx + d, cy - d - h, cx + d + w, cy - d};
      for (const Box& box : {Box{cx + d, cy - d - h, cx + d + w, cy - d}, Box{cx + d, cy + d, cx + d + w, cy + d + h},
                             Box{cx - d - w, cy - d - h, cx - d, cy - d}, Box{cx - d - w, cy + d, cx - d, cy + d + h}})
        if (box.x0 >= frame.left && box.x1 <= frame.right && box.y0 >= frame.top &&
            std::none_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(box); })) {
          chosen = box;
          break;
        }
      taken.push_back(chosen);
      canvas.colour(method_colour(method));
      canvas.text(chosen.x0, chosen.y1, text, Align::start, Align::end);
    }
  canvas.font_size(font);
}

void time_panel(Canvas& canvas, const Runs& runs, const Frame& frame) {
  const auto [x_low, x_high] = decade_range(runs.increments, {-4, -2});
  const auto [y_low, y_high] = decade_range(runs.times, {-1, 1});
  const Axis x{x_low, x_high, frame.left, frame.right, true};
  const Axis y{y_low, y_high, frame.bottom, frame.top, true};
  draw_axes(canvas, frame, x, log_ticks(x), y, log_ticks(y), {"increment ds", "wall time (s)"}, true);
  if (runs.reference) {
    const double at = y.position(std::max(runs.reference->wall_seconds, 1e-300));
    canvas.colour(reference_colour);
    canvas.line_width(1.5);
    canvas.dash(6, 4);
    canvas.segment(frame.left, at, frame.right, at);
    canvas.stroke();
    canvas.dash(0, 0);
    canvas.text(frame.right - 0.4 * font, at - 0.5 * font, "reference", Align::end, Align::end);
  }
  for (const auto& [method, rows] : runs.by_method) {
    std::vector<std::pair<double, double>> points;
    for (const StudyRow* row : rows)
      if (row->increment && *row->increment > 0)
        points.push_back({x.position(*row->increment), y.position(std::max(row->wall_seconds, 1e-300))});
    series(canvas, points, true, method_colour(method));
  }
}

void legend(Canvas& canvas, const Runs& runs, double left, double middle) {
  double x = left;
  auto advance = [&](const std::string& text) {
    canvas.colour(ink_colour);
    canvas.text(x + 1.6 * font, middle, text, Align::start, Align::centre);
    x += 1.6 * font + canvas.text_width(text) + 1.6 * font;
  };
  marker_at(canvas, x + 0.6 * font, middle, true, ink_colour);
  advance("broken-set difference");
  marker_at(canvas, x + 0.6 * font, middle, false, ink_colour);
  advance("first-break error (0: on the bottom edge)");
  for (const auto& [method, rows] : runs.by_method) {
    canvas.colour(method_colour(method));
    canvas.rectangle(x, middle - 2, 1.2 * font, 4);
    canvas.fill();
    advance(method);
  }
  if (runs.reference) {
    canvas.colour(reference_colour);
    for (int dash = 0; dash < 2; ++dash) canvas.rectangle(x + dash * 0.7 * font, middle - 1, 0.45 * font, 2);
    canvas.fill();
    advance("reference: " + runs.reference->method +
            (runs.reference->increment ? " ds=" + increment_text(*runs.reference->increment) : ""));
  }
}

}  // namespace

void write_study_plot(const StudyResult& study, const std::string& path) {
  const Runs runs = gather(study);
  draw_picture_file(path, width, height, [&](Canvas& canvas) {
    canvas.font_size(1.15 * font);
    canvas.colour(ink_colour);
    canvas.text(width / 2.0, 1.4 * font, study.scene_name + ": convergence study", Align::centre,
                Align::centre);
    canvas.font_size(font);
    const double top = 3 * font, bottom = height - 6.5 * font;
    error_panel(canvas, runs, {6 * font, top, width / 2.0 - 2 * font, bottom});
    time_panel(canvas, runs, {width / 2.0 + 5 * font, top, width - 2 * font, bottom});
    legend(canvas, runs, 6 * font, height - 1.5 * font);
  });
}

}  // namespace latfrac
