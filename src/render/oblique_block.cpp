// The oblique view's block outline and its edge axes in km.
#include "oblique_block.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "colour_map.h"

namespace latfrac {
namespace {

constexpr Colour hidden_colour{170, 170, 170};

struct Pixel {
  double x = 0, y = 0;
};

Pixel pixel_of(const SceneView& view, const PictureLayout& layout, const Vec3& p) {
  const ViewPoint at = view.project(p);
  return {layout.x(at), layout.y(at)};
}

Vec3 corner(const SceneView& view, int index) {
  return {index & 1 ? view.box_high[0] : view.box_low[0], index & 2 ? view.box_high[1] : view.box_low[1],
          index & 4 ? view.box_high[2] : view.box_low[2]};
}

// Ticks along the edge from `start` along `axis` to the box's other face, labels on the
// side away from the block's middle.
void edge_axis(Canvas& canvas, const SceneView& view, const PictureLayout& layout, Vec3 start,
               int axis, const char* title) {
  const double f = layout.font;
  Vec3 end = start;
  end[axis] = view.box_high[axis];
  const Pixel a = pixel_of(view, layout, start), b = pixel_of(view, layout, end);
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  if (length < 2 * f) return;
  Pixel out{-(b.y - a.y) / length, (b.x - a.x) / length};
  Vec3 middle;
  for (int i = 0; i < 3; ++i) middle[i] = 0.5 * (view.box_low[i] + view.box_high[i]);
  const Pixel centre = pixel_of(view, layout, middle);
  if (out.x * (0.5 * (a.x + b.x) - centre.x) + out.y * (0.5 * (a.y + b.y) - centre.y) < 0)
    out = {-out.x, -out.y};

  const double low = view.box_low[axis], high = view.box_high[axis];
  const double step = nice_step_at_least((high - low) * 3 * f / length);
  canvas.colour(ink_colour);
  double reach = 0;  // of the labels, away from the edge
  for (double k = std::ceil(low / step - 1e-9); k * step <= high + 1e-9 * step; k += 1) {
    Vec3 p = start;
    p[axis] = k * step;
    const Pixel at = pixel_of(view, layout, p);
    canvas.segment(at.x, at.y, at.x + 0.5 * f * out.x, at.y + 0.5 * f * out.y);
    char label[32];
    std::snprintf(label, sizeof label, "%g", std::abs(k * step) < 1e-9 ? 0.0 : k * step / 1000);
    const double half_width = 0.5 * canvas.text_width(label);
    const double across = half_width * std::abs(out.x) + 0.4 * f * std::abs(out.y);
    canvas.text(at.x + (0.8 * f + across) * out.x, at.y + (0.8 * f + across) * out.y, label,
                Align::centre, Align::centre);
    reach = std::max(reach, 0.8 * f + 2 * across);
  }
  canvas.stroke();
  const double across = 0.5 * canvas.text_width(title) * std::abs(out.x) + 0.4 * f * std::abs(out.y);
  canvas.text(0.5 * (a.x + b.x) + (reach + 0.6 * f + across) * out.x,
              0.5 * (a.y + b.y) + (reach + 0.6 * f + across) * out.y, title, Align::centre,
              Align::centre);
}

}  // namespace

void draw_block(Canvas& canvas, const SceneView& view, const PictureLayout& layout) {
  int farthest = 0;
  for (int i = 1; i < 8; ++i)
    if (view.depth(corner(view, i)) > view.depth(corner(view, farthest))) farthest = i;
  const double line = std::max(1.0, layout.font / 10);
  for (const bool hidden : {true, false}) {
    canvas.colour(hidden ? hidden_colour : ink_colour);
    canvas.line_width(line);
    canvas.dash(hidden ? 0.5 * layout.font : 0, 0.3 * layout.font);
    for (int i = 0; i < 8; ++i)
      for (int bit : {1, 2, 4}) {
        if (i & bit) continue;
        const int j = i | bit;
        if ((i == farthest || j == farthest) != hidden) continue;
        const Pixel a = pixel_of(view, layout, corner(view, i)), b = pixel_of(view, layout, corner(view, j));
        canvas.segment(a.x, a.y, b.x, b.y);
      }
    canvas.stroke();
  }
  canvas.dash(0, 0);
  // The near corner of the bottom face: x and y run from there, z rises from it.
  int near = 0;
  for (int i = 1; i < 4; ++i)
    if (view.depth(corner(view, i)) < view.depth(corner(view, near))) near = i;
  const Vec3 base = corner(view, near);
  Vec3 x_start = base, y_start = base, z_start = base;
  x_start[0] = view.box_low[0];
  y_start[1] = view.box_low[1];
  z_start[2] = view.box_low[2];
  edge_axis(canvas, view, layout, x_start, 0, "x (km)");
  edge_axis(canvas, view, layout, y_start, 1, "y (km)");
  // z up the vertical edge at the low-x end of the near x edge, left of the block.
  z_start[0] = view.box_low[0];
  edge_axis(canvas, view, layout, z_start, 2, "z (km)");
}

}  // namespace latfrac
