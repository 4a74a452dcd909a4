// The layers of a snapshot picture: layout, particles, crack segments, colour bar, legend row.
#include "picture_layers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "colour_map.h"

namespace latfrac {
namespace {

std::string number_label(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value == 0 ? 0.0 : value);
  return std::string(text) == "-0" ? "0" : text;
}

}  // namespace

PictureLayout layout_picture(const SceneView& view, int width, bool axes, bool colour_bar) {
  PictureLayout layout;
  layout.width = width;
  layout.colour_bar = colour_bar;
  layout.font = std::clamp(width / 100.0, 9.0, 60.0);
  const double f = layout.font;
  const double top = 2.6 * f, left = axes ? 5.4 * f : 1.2 * f, right = colour_bar ? 9 * f : 1.5 * f;
  const double below_plot = axes ? 4.4 * f : 0.8 * f, legend_row = 2.2 * f;
  const double plot_width = width - left - right;

  double h_min = view.h_min, h_max = view.h_max, v_min = view.v_min, v_max = view.v_max;
  const double aspect = (v_max - v_min) / (h_max - h_min);
  const double plot_height = plot_width * std::clamp(aspect, 0.05, 2.5);
  if (aspect < 0.05) {  // widen v about its middle
    const double middle = 0.5 * (v_min + v_max), half = 0.5 * 0.05 * (h_max - h_min);
    v_min = middle - half, v_max = middle + half;
  } else if (aspect > 2.5) {  // widen h
    const double middle = 0.5 * (h_min + h_max), half = 0.5 * (v_max - v_min) / 2.5;
    h_min = middle - half, h_max = middle + half;
  }
  layout.frame = {left, top, left + plot_width, top + plot_height};
  layout.h = {h_min, h_max, left, left + plot_width};
  layout.v = {v_min, v_max, top + plot_height, top};
  layout.legend_y = top + plot_height + below_plot + 0.5 * legend_row;
  layout.height = static_cast<int>(std::ceil(top + plot_height + below_plot + legend_row));
  return layout;
}

double particle_radius(double spacing) {
  return spacing >= 10 ? 0.45 * spacing : std::max(1.0, 0.6 * spacing + 0.5);
}

void draw_nodes(Canvas& canvas, const std::vector<ViewNode>& nodes, const PictureLayout& layout,
                const std::vector<Colour>& colours, double radius) {
  // A few shapes of one colour share a path: fewer fills, and Cairo's cost of a path
  // grows faster than its length when shapes overlap.
  constexpr std::size_t shapes_per_fill = 16;
  const bool squares = radius < 3;
  const double half_side = radius * std::sqrt(std::numbers::pi) / 2;
  std::size_t in_path = 0;
  Colour current;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (in_path > 0 && (colours[i] != current || in_path == shapes_per_fill)) {
      canvas.fill();
      in_path = 0;
    }
    if (in_path == 0) canvas.colour(current = colours[i]);
    const double x = layout.x(nodes[i].at), y = layout.y(nodes[i].at);
    if (squares)
      canvas.rectangle(x - half_side, y - half_side, 2 * half_side, 2 * half_side);
    else
      canvas.circle(x, y, radius);
    ++in_path;
  }
  if (in_path > 0) canvas.fill();
}

double crack_width(const SceneView& view, const PictureLayout& layout) {
  const double spacing = view.spacing * layout.pixels_per_m();
  return view.kind == PictureView::oblique ? std::clamp(0.08 * spacing, 1.5, 4.0)
                                           : std::clamp(0.15 * spacing, 2.5, 5.0);
}

void draw_cracks(Canvas& canvas, const SceneView& view, const PictureLayout& layout, bool casing,
                 bool depth_cue) {
  if (view.broken.empty()) return;
  const double width = crack_width(view, layout);
  double near = view.broken.front().depth, far = near;
  for (const ViewBond& bond : view.broken)
    near = std::min(near, bond.depth), far = std::max(far, bond.depth);
  // Depth cue: the farthest bonds fade 60 % of the way to the paper and are 40 % thinner.
  auto farness = [&](const ViewBond& bond) {
    return depth_cue && far > near ? (bond.depth - near) / (far - near) : 0.0;
  };
  canvas.round_caps();
  if (casing) {
    canvas.colour(paper_colour);
    for (const ViewBond& bond : view.broken) {
      canvas.line_width((1 - 0.4 * farness(bond)) * width + 2 * std::max(1.0, width / 3));
      canvas.segment(layout.x(bond.from), layout.y(bond.from), layout.x(bond.to), layout.y(bond.to));
      canvas.stroke();
    }
  }
  for (const ViewBond& bond : view.broken) {
    const double t = farness(bond);
    canvas.colour(mix(mode_colour(bond.mode), paper_colour, 0.6 * t));
    canvas.line_width((1 - 0.4 * t) * width);
    canvas.segment(layout.x(bond.from), layout.y(bond.from), layout.x(bond.to), layout.y(bond.to));
    canvas.stroke();
  }
}

std::pair<std::string, std::string> draw_colour_bar(Canvas& canvas, const PictureLayout& layout,
                                                    double low, double high,
                                                    const std::string& title) {
  const double f = layout.font;
  const double x = layout.frame.right + 1.2 * f, bar = 1.1 * f;
  const double top = layout.frame.top, bottom = layout.frame.bottom;
  std::vector<Colour> colours;
  if (high > low) {
    for (int i = 0; i <= 32; ++i) colours.push_back(field_colour(i / 32.0));
  } else {
    colours.push_back(field_colour(0.5));
  }
  canvas.fill_gradient(x, top, bar, bottom - top, colours);
  canvas.colour(ink_colour);
  canvas.line_width(std::max(1.0, f / 16));
  canvas.rectangle(x, top, bar, bottom - top);
  canvas.stroke();

  const std::string low_label = number_label(low), high_label = number_label(high);
  std::vector<std::pair<double, std::string>> labels{{bottom, low_label}, {top, high_label}};
  if (high > low) {  // inner ticks at a nice step, clear of the end labels
    const Axis axis{low, high, bottom, top};
    const double step = nice_step_at_least((high - low) * 4 * f / (bottom - top));
    for (double k = std::ceil(low / step); k * step < high; k += 1) {
      const double y = axis.position(k * step);
      if (y < bottom - 1.6 * f && y > top + 1.6 * f) labels.push_back({y, number_label(k * step)});
    }
  }
  double widest = 0;
  for (const auto& [y, label] : labels) {
    canvas.segment(x + bar, y, x + bar + 0.3 * f, y);
    canvas.text(x + bar + 0.5 * f, y, label, Align::start, Align::centre);
    widest = std::max(widest, canvas.text_width(label));
  }
  canvas.stroke();
  canvas.text(x + bar + 0.9 * f + widest, 0.5 * (top + bottom), title, Align::centre, Align::start,
              true);
  return {low_label, high_label};
}

void draw_legend_row(Canvas& canvas, const PictureLayout& layout,
                     const std::vector<LegendEntry>& entries) {
  const double f = layout.font, y = layout.legend_y;
  // The scale bar: a nice length between a tenth and a quarter of the plot's width.
  const double metres = nice_step_at_least((layout.h.high - layout.h.low) / 10);
  const double length = metres * layout.pixels_per_m();
  double x = layout.frame.left;
  canvas.colour(ink_colour);
  canvas.rectangle(x, y - 0.15 * f, length, 0.3 * f);
  canvas.rectangle(x, y - 0.4 * f, std::max(1.0, f / 10), 0.8 * f);
  canvas.rectangle(x + length - std::max(1.0, f / 10), y - 0.4 * f, std::max(1.0, f / 10), 0.8 * f);
  canvas.fill();
  char text[32];
  std::snprintf(text, sizeof text, "%g km", metres / 1000);
  canvas.text(x + length + 0.5 * f, y, text, Align::start, Align::centre);
  x += length + 0.5 * f + canvas.text_width(text) + 2.5 * f;

  for (const LegendEntry& entry : entries) {
    canvas.colour(entry.colour);
    switch (entry.symbol) {
      case LegendEntry::Symbol::line:
        canvas.rectangle(x, y - 0.15 * f, 1.6 * f, 0.3 * f);
        break;
      case LegendEntry::Symbol::dashed_line:
        for (int dash = 0; dash < 3; ++dash) canvas.rectangle(x + dash * 0.6 * f, y - 0.08 * f, 0.4 * f, 0.16 * f);
        break;
      case LegendEntry::Symbol::disc:
        canvas.circle(x + 0.8 * f, y, 0.35 * f);
        break;
      case LegendEntry::Symbol::swatch:
        canvas.rectangle(x + 0.2 * f, y - 0.4 * f, 1.2 * f, 0.8 * f);
        break;
    }
    canvas.fill();
    canvas.colour(ink_colour);
    canvas.text(x + 2 * f, y, entry.text, Align::start, Align::centre);
    x += 2 * f + canvas.text_width(entry.text) + 1.5 * f;
  }
}

std::vector<LegendEntry> crack_legend(const SceneView& view) {
  std::array<std::size_t, 4> counts{};  // tensile, shear, pre-cut, no event
  for (const ViewBond& bond : view.broken) ++counts[bond.mode >= 0 && bond.mode <= 2 ? bond.mode : 3];
  const std::array<const char*, 4> names{"tensile", "shear", "pre-cut", "no break event"};
  std::vector<LegendEntry> entries;
  for (std::size_t mode = 0; mode < counts.size(); ++mode)
    if (counts[mode] > 0)
      entries.push_back({LegendEntry::Symbol::line, mode_colour(static_cast<std::int8_t>(mode < 3 ? mode : -1)),
                         std::string(names[mode]) + " (" + std::to_string(counts[mode]) + ")"});
  if (entries.empty()) entries.push_back({LegendEntry::Symbol::line, lattice_colour, "no broken bond"});
  if (view.min_offset > 0) {
    char moved[64];
    std::snprintf(moved, sizeof moved, "moved %g m or more: ", view.min_offset);
    entries.front().text = moved + entries.front().text;
  }
  return entries;
}

}  // namespace latfrac
