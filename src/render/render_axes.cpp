// Picture layout and axes: margins, frame, 'nice' km ticks, axis titles and the title.
#include "render_axes.h"

#include <algorithm>
#include <cstdio>

#include "bitmap_font.h"

namespace latfrac {
namespace {

constexpr Rgb axis_ink{25, 25, 25};

// Sizes in pixels, all proportional to the text scale.
struct Metrics {
  int scale, line, tick, gap, cap, cell, advance;

  explicit Metrics(int text_scale)
      : scale(text_scale),
        line(std::max(1, (text_scale + 1) / 2)),
        tick(3 * text_scale),
        gap(3 * text_scale),
        cap(text_cap_height(text_scale)),
        cell(glyph_rows * text_scale),
        advance(glyph_advance * text_scale) {}
};

constexpr int z_label_budget_chars = 7;

double nice_step_at_least(double value) {
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  for (double mantissa : {1.0, 2.0, 5.0})
    if (mantissa * decade >= value * (1 - 1e-9)) return mantissa * decade;
  return 10 * decade;
}

std::string km_label(double metres, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step / 1000) + 1e-9)));
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, metres / 1000);
  std::string label = text;
  if (label[0] == '-' && label.find_first_not_of("-0.") == std::string::npos) label.erase(0, 1);
  return label;
}

}  // namespace

SectionLayout layout_section(const SectionWindow& window, int width) {
  SectionLayout layout;
  layout.width = width;
  layout.text_scale = std::max(1, static_cast<int>(std::lround(width / 500.0)));
  const Metrics m(layout.text_scale);
  const int left =
      m.gap + m.cell + 2 * m.gap + z_label_budget_chars * m.advance + m.gap + m.tick + m.line;
  const int right = 4 * m.advance;
  const int top = 4 * m.cap;
  const int bottom = m.line + m.tick + m.gap + m.cell + 2 * m.gap + m.cell + 2 * m.gap;
  const int plot_width = width - left - right;
  const double aspect = (window.z_max - window.z_min) / (window.x_max - window.x_min);
  const int plot_height = std::clamp(static_cast<int>(std::lround(plot_width * aspect)),
                                     std::max(20, plot_width / 20), 3 * plot_width);
  layout.height = top + plot_height + bottom;
  layout.x = {window.x_min, window.x_max, left, left + plot_width};
  layout.z = {window.z_min, window.z_max, top + plot_height, top};
  return layout;
}

std::vector<Tick> choose_ticks(const AxisMap& axis, bool labels_side_by_side, int text_scale) {
  double step = nice_step_at_least((axis.high - axis.low) / 12);
  while (true) {
    std::vector<Tick> ticks;
    for (double k = std::ceil(axis.low / step - 1e-9); k * step <= axis.high + 1e-9 * step; k += 1)
      ticks.push_back({k * step, km_label(k * step, step)});
    int widest = 0;
    for (const Tick& tick : ticks) widest = std::max(widest, text_width(tick.label, text_scale));
    const double needed = labels_side_by_side ? widest + 3 * glyph_advance * text_scale
                                              : 3.0 * text_cap_height(text_scale);
    if (step * axis.pixels_per_unit() >= needed || ticks.size() <= 2) return ticks;
    step = nice_step_at_least(step * 1.5);
  }
}

void draw_axes(Canvas& canvas, const SectionLayout& layout, const std::string& title) {
  const Metrics m(layout.text_scale);
  const int left = layout.x.pixel_at_low, right = layout.x.pixel_at_high;
  const int top = layout.z.pixel_at_high, bottom = layout.z.pixel_at_low;

  canvas.fill_rect(left - m.line, top - m.line, right + 1 + m.line, top, axis_ink);
  canvas.fill_rect(left - m.line, bottom + 1, right + 1 + m.line, bottom + 1 + m.line, axis_ink);
  canvas.fill_rect(left - m.line, top, left, bottom + 1, axis_ink);
  canvas.fill_rect(right + 1, top, right + 1 + m.line, bottom + 1, axis_ink);

  const int x_label_top = bottom + 1 + m.line + m.tick + m.gap;
  for (const Tick& tick : choose_ticks(layout.x, true, m.scale)) {
    const int x = layout.x.pixel(tick.value);
    canvas.fill_rect(x - m.line / 2, bottom + 1 + m.line, x - m.line / 2 + m.line,
                     bottom + 1 + m.line + m.tick, axis_ink);
    canvas.text(x - text_width(tick.label, m.scale) / 2, x_label_top, tick.label, m.scale,
                axis_ink);
  }
  const std::string x_title = "x (km)";
  canvas.text((left + right - text_width(x_title, m.scale)) / 2, x_label_top + m.cell + 2 * m.gap,
              x_title, m.scale, axis_ink);

  const int z_label_right = left - m.line - m.tick - m.gap;
  int z_labels_left = z_label_right;
  for (const Tick& tick : choose_ticks(layout.z, false, m.scale)) {
    const int y = layout.z.pixel(tick.value);
    canvas.fill_rect(left - m.line - m.tick, y - m.line / 2, left - m.line, y - m.line / 2 + m.line,
                     axis_ink);
    const int label_left = z_label_right - text_width(tick.label, m.scale);
    canvas.text(label_left, y - m.cap / 2, tick.label, m.scale, axis_ink);
    z_labels_left = std::min(z_labels_left, label_left);
  }
  const std::string z_title = "z (km)";
  canvas.vertical_text(z_labels_left - 2 * m.gap - m.cell,
                       (top + bottom + text_width(z_title, m.scale)) / 2, z_title, m.scale,
                       axis_ink);

  int title_scale = m.scale;
  while (title_scale > 1 && text_width(title, title_scale) > canvas.width() - 2 * m.gap)
    --title_scale;
  const int title_width = text_width(title, title_scale);
  const int title_x = std::max(
      m.gap, std::min((left + right - title_width) / 2, canvas.width() - m.gap - title_width));
  canvas.text(title_x, (top - m.line - text_cap_height(title_scale)) / 2, title, title_scale,
              axis_ink);
}

}  // namespace latfrac
