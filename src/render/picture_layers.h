// The layers of a snapshot picture: its layout, nodes, cracks, colour bar, scale bar, legend.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "canvas.h"
#include "plot_axes.h"
#include "scene_view.h"

namespace latfrac {

// Where everything goes. The plot maps the view's window onto `frame` with equal scales
// on h and v (the window is widened along one of them when the frame's shape is clamped).
struct PictureLayout {
  int width = 0, height = 0;
  double font = 12;      // label size, pixels
  Frame frame;
  Axis h, v;             // picture plane (m) to pixels
  double legend_y = 0;   // the middle of the row under the plot: scale bar and legend
  bool colour_bar = false;

  double pixels_per_m() const { return h.pixels_per_unit(); }
  double x(const ViewPoint& p) const { return h.position(p.h); }
  double y(const ViewPoint& p) const { return v.position(p.v); }
};

// Lays out a picture `width` wide for `view`; axes leave room for tick labels and titles,
// a colour bar for itself.
PictureLayout layout_picture(const SceneView& view, int width, bool axes, bool colour_bar);

// The radius of a particle's dot, pixels, for particles `spacing` pixels apart: 0.45 of the
// spacing when dots are 10 px apart or more, so each shows with a gap at every bond; closer
// dots are drawn solid (0.6 spacing + 0.5 px covers the middle of every triangle of
// neighbours), because gaps under a pixel wide, falling on the same pixel rows, once drew
// white lines that looked like cracks.
double particle_radius(double spacing);

// Each node as a particle in its colour (colours[i] for nodes[i]), in order; nodes drawn
// under a few pixels are squares of the disc's area, which look alike and draw faster.
void draw_nodes(Canvas& canvas, const std::vector<ViewNode>& nodes, const PictureLayout& layout,
                const std::vector<Colour>& colours, double radius);

// Each broken bond a segment, one stroke per bond, in its mode's colour; `casing` draws a
// white band under each (over a field), `depth_cue` fades and thins far ones (oblique).
void draw_cracks(Canvas& canvas, const SceneView& view, const PictureLayout& layout, bool casing,
                 bool depth_cue);

// The width of a crack segment, pixels: at least 2.5 px in sections and maps, so that the
// pixel at a bond's midpoint is wholly in its mode's colour; thinner in the oblique view,
// where bonds crowd.
double crack_width(const SceneView& view, const PictureLayout& layout);

// The colour bar at the right of the frame, from `low` to `high` (display units), its
// title above; returns the end labels, low and high.
std::pair<std::string, std::string> draw_colour_bar(Canvas& canvas, const PictureLayout& layout,
                                                    double low, double high,
                                                    const std::string& title);

// One entry of the legend: a symbol and its text.
struct LegendEntry {
  enum class Symbol { line, dashed_line, disc, swatch } symbol = Symbol::line;
  Colour colour;
  std::string text;
};

// The scale bar (a nice length in km) at the left of the row under the plot, the legend's
// entries side by side at its right.
void draw_legend_row(Canvas& canvas, const PictureLayout& layout,
                     const std::vector<LegendEntry>& entries);

// The entries for the cracks drawn: one per break mode present, with its count.
std::vector<LegendEntry> crack_legend(const SceneView& view);

}  // namespace latfrac
