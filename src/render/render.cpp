// A snapshot picture: the options checked, the view made, then its layers drawn in order.
#include "latfrac/render/render.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "canvas.h"
#include "colour_map.h"
#include "fault_overlay.h"
#include "latfrac/analysis/fault_analysis.h"
#include "latfrac/base/error.h"
#include "latfrac/render/node_field.h"
#include "oblique_block.h"
#include "picture_layers.h"
#include "scene_view.h"

namespace latfrac {
namespace {

void check_result(const RunResult& result, std::size_t index, const PictureOptions& options) {
  if (index >= result.snapshots.size())
    throw InputError("render: snapshot " + std::to_string(index) +
                     " does not exist (the result has " + std::to_string(result.snapshots.size()) +
                     ")");
  if (options.width < 200 || options.width > 20000)
    throw InputError("render: width " + std::to_string(options.width) +
                     " px is out of range (200 to 20000)");
  if (!std::isfinite(options.exaggeration))
    throw InputError("render: the exaggeration must be a finite number");
  if (!(options.min_offset >= 0) || !std::isfinite(options.min_offset))
    throw InputError("render: the least offset (--min-offset) must be 0 or more (m) and finite");
  if (options.exaggeration < 0 &&
      !(std::isfinite(result.scene.exaggeration) && result.scene.exaggeration >= 0))
    throw InputError("render: the scene's exaggeration must be a finite number >= 0");
  if (result.scene.dim != 2 && result.scene.dim != 3)
    throw InputError("render: dim is " + std::to_string(result.scene.dim) + ", not 2 or 3");
  const std::size_t nodes = result.node_count();
  if (nodes == 0 || result.positions.size() % 3 != 0)
    throw InputError("render: the result has " + std::to_string(result.positions.size()) +
                     " position values; need 3 per node and at least one node");
  if (result.bonds.size() != 2 * result.bond_count())
    throw InputError("render: the result has " + std::to_string(result.bonds.size()) +
                     " bond node indices for " + std::to_string(result.bond_count()) + " bonds");
  for (std::int64_t node : result.bonds)
    if (node < 0 || static_cast<std::size_t>(node) >= nodes)
      throw InputError("render: a bond names node " + std::to_string(node) + " of " +
                       std::to_string(nodes));
  const Snapshot& snapshot = result.snapshots[index];
  if (snapshot.displacement.size() != 3 * nodes)
    throw InputError("render: snapshot " + std::to_string(index) + " has " +
                     std::to_string(snapshot.displacement.size()) + " displacement values for " +
                     std::to_string(nodes) + " nodes");
  if (snapshot.bond_intact.size() != result.bond_count())
    throw InputError("render: snapshot " + std::to_string(index) + " has " +
                     std::to_string(snapshot.bond_intact.size()) + " bond_intact values for " +
                     std::to_string(result.bond_count()) + " bonds");
}

std::string title_text(const RunResult& result, const Snapshot& snapshot, const SceneView& view) {
  char numbers[128];
  std::snprintf(numbers, sizeof numbers, "λ = %#.4g    exaggeration ×%g", snapshot.lambda,
                view.exaggeration);
  std::string title;
  if (!result.scene.name.empty()) title += result.scene.name + "    ";
  title += (result.scene.criterion.empty() ? "elastic" : result.scene.criterion) + "    " + numbers;
  return view.where.empty() ? title : title + "    " + view.where;
}

// The field's values at the view's nodes, and their finite range.
struct FieldOnView {
  std::vector<double> values;
  double low = 0, high = 0;
  bool any = false;
};

FieldOnView field_on_view(const RunResult& result, const Snapshot& snapshot, const SceneView& view,
                          NodeField field) {
  FieldOnView on_view;
  if (field == NodeField::none) return on_view;
  const std::vector<double> all = node_field(result, snapshot, field);
  for (const ViewNode& node : view.nodes) {
    const double value = all[node.node];
    on_view.values.push_back(value);
    if (!std::isfinite(value)) continue;
    on_view.low = on_view.any ? std::min(on_view.low, value) : value;
    on_view.high = on_view.any ? std::max(on_view.high, value) : value;
    on_view.any = true;
  }
  return on_view;
}

// The nodes in drawing order with their colours: the field's, or the style's; the
// particles that touch a broken bond last, on top.
void draw_lattice(Canvas& canvas, const SceneView& view, const PictureLayout& layout,
                  const PictureOptions& options, const FieldOnView& field) {
  std::vector<ViewNode> nodes, touching;
  std::vector<Colour> colours, touching_colours;
  const bool particles = options.style == CrackStyle::particles && view.kind != PictureView::oblique;
  for (std::size_t i = 0; i < view.nodes.size(); ++i) {
    Colour colour = particles ? particle_colour : lattice_colour;
    if (options.field != NodeField::none)
      colour = field_colour(field.high > field.low ? (field.values[i] - field.low) / (field.high - field.low)
                                                   : std::isnan(field.values[i]) ? field.values[i] : 0.5);
    if (particles && view.touches_broken[view.nodes[i].node]) {
      touching.push_back(view.nodes[i]);
      touching_colours.push_back(broken_particle_colour);
    } else {
      nodes.push_back(view.nodes[i]);
      colours.push_back(colour);
    }
  }
  const double spacing = view.spacing * layout.pixels_per_m();
  const double radius = view.kind == PictureView::oblique ? std::max(0.6, 0.15 * spacing)
                                                          : particle_radius(spacing);
  draw_nodes(canvas, nodes, layout, colours, radius);
  draw_nodes(canvas, touching, layout, touching_colours, radius);
}

}  // namespace

std::array<double, 2> PictureReport::pixel_of(const std::array<double, 3>& position) const {
  const double h = right[0] * position[0] + right[1] * position[1] + right[2] * position[2];
  const double v = up[0] * position[0] + up[1] * position[1] + up[2] * position[2];
  return {frame[0] + (h - window[0]) / (window[1] - window[0]) * (frame[2] - frame[0]),
          frame[3] - (v - window[2]) / (window[3] - window[2]) * (frame[3] - frame[1])};
}

std::size_t snapshot_nearest(const RunResult& result, double lambda) {
  if (result.snapshots.empty()) throw InputError("render: the result has no snapshots");
  if (std::isnan(lambda)) return result.snapshots.size() - 1;
  // Beyond the snapshots' range the nearest is the end on that side; the distances alone
  // would tie there when lambda dwarfs them (|1e15 - 0.01| == |1e15 - 0.04| in doubles).
  std::size_t lowest = 0, highest = 0;
  for (std::size_t i = 1; i < result.snapshots.size(); ++i) {
    if (result.snapshots[i].lambda < result.snapshots[lowest].lambda) lowest = i;
    if (result.snapshots[i].lambda > result.snapshots[highest].lambda) highest = i;
  }
  if (lambda >= result.snapshots[highest].lambda) return highest;
  if (lambda <= result.snapshots[lowest].lambda) return lowest;
  std::size_t nearest = 0;
  for (std::size_t i = 1; i < result.snapshots.size(); ++i)
    if (std::abs(result.snapshots[i].lambda - lambda) <
        std::abs(result.snapshots[nearest].lambda - lambda))
      nearest = i;
  return nearest;
}

// The window holds the reference and the deformed positions (fit_window), so an
// exaggeration that moves the nodes far beyond the lattice's size shrinks the lattice to
// a speck. Not an error (the user asked for it), but worth saying, with a value that fits:
// the largest motion a fifth of the lattice's size.
std::string exaggeration_note(const RunResult& result, const Snapshot& snapshot,
                              double exaggeration) {
  const double size = result.largest_extent();
  double largest = 0;
  for (const double u : snapshot.displacement) largest = std::max(largest, std::abs(u));
  if (!(size > 0) || !(largest > 0) || !(exaggeration * largest > 10 * size)) return "";
  char text[400];
  std::snprintf(text, sizeof text,
                "the exaggeration %g moves nodes by up to %.3g m, %.3g times the lattice's "
                "size (%.3g m): the lattice is drawn small; an exaggeration of about %.2g "
                "fits (the largest motion a fifth of the size)",
                exaggeration, exaggeration * largest, exaggeration * largest / size, size,
                0.2 * size / largest);
  return text;
}

PictureReport render_picture(const RunResult& result, std::size_t index, const std::string& path,
                             const PictureOptions& options) {
  // 1. Everything that can be wrong with the input, before any file is made.
  picture_format_of(path);
  check_result(result, index, options);
  const Snapshot& snapshot = result.snapshots[index];
  const double exaggeration =
      options.exaggeration >= 0 ? options.exaggeration : result.scene.exaggeration;
  const SceneView view = make_view(result, snapshot, options, exaggeration);
  const FieldOnView field = field_on_view(result, snapshot, view, options.field);
  std::optional<FaultReport> faults;
  if (options.faults) {
    FaultOptions fault_options;
    fault_options.min_offset = options.min_offset;
    faults = analyze_faults(result, index, fault_options);
  }

  // 2. The layout, and what it tells the caller.
  const bool oblique = view.kind == PictureView::oblique;
  const PictureLayout layout =
      layout_picture(view, options.width, !oblique, options.field != NodeField::none);
  PictureReport report;
  report.width = layout.width, report.height = layout.height;
  report.frame = {layout.frame.left, layout.frame.top, layout.frame.right, layout.frame.bottom};
  report.window = {layout.h.low, layout.h.high, layout.v.low, layout.v.high};
  report.right = view.right, report.up = view.up;
  report.field_min = field.low, report.field_max = field.high;
  report.nodes_drawn = view.nodes.size();
  report.note = exaggeration_note(result, snapshot, exaggeration);
  const bool cracks = options.style == CrackStyle::cracks || oblique;
  report.broken_bonds_drawn = cracks ? view.broken.size() : 0;

  // 3. The layers, back to front.
  draw_picture_file(path, layout.width, layout.height, [&](Canvas& canvas) {
    canvas.font_size(1.15 * layout.font);
    canvas.colour(ink_colour);
    canvas.text(0.5 * layout.width, 1.2 * layout.font, title_text(result, snapshot, view),
                Align::centre, Align::centre);
    canvas.font_size(layout.font);
    if (oblique) draw_block(canvas, view, layout);
    draw_lattice(canvas, view, layout, options, field);
    std::vector<LegendEntry> legend, fault_legend;
    auto fault_layer = [&](FaultLayer layer) {
      if (faults) fault_legend = draw_faults(canvas, view, layout, result, snapshot, *faults, layer);
    };
    fault_layer(FaultLayer::areas);  // under the cracks
    if (cracks) {
      draw_cracks(canvas, view, layout, options.field != NodeField::none, oblique);
      legend = crack_legend(view);
    } else {
      legend.push_back({LegendEntry::Symbol::disc, broken_particle_colour, "touches a broken bond"});
    }
    fault_layer(FaultLayer::lines);
    fault_layer(FaultLayer::labels);
    legend.insert(legend.end(), fault_legend.begin(), fault_legend.end());
    if (!oblique) {
      const std::vector<Tick> h_ticks = linear_ticks(canvas, layout.h, 1000, true);
      const std::vector<Tick> v_ticks = linear_ticks(canvas, layout.v, 1000, false);
      draw_axes(canvas, layout.frame, layout.h, h_ticks, layout.v, v_ticks,
                {view.h_title, view.v_title});
    }
    if (options.field != NodeField::none) {
      const FieldLabel label = field_label(options.field);
      const std::string title = label.unit.empty() ? label.title : label.title + " (" + label.unit + ")";
      const auto [low, high] = draw_colour_bar(canvas, layout, field.low * label.per_si,
                                               field.high * label.per_si, title);
      report.colour_bar_low = low, report.colour_bar_high = high;
    }
    draw_legend_row(canvas, layout, legend);
  });
  return report;
}

}  // namespace latfrac
