// Cross-section pictures of a snapshot: which nodes to draw, where, and in which colour.
#include "latfrac/render/render.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "latfrac/base/error.h"
#include "raster.h"
#include "render_axes.h"

namespace latfrac {
namespace {

constexpr Rgb background{255, 255, 255};
constexpr Rgb node_grey{90, 90, 90};
constexpr Rgb broken_red{220, 20, 20};

void check_result(const RunResult& result, std::size_t index, const RenderOptions& options) {
  if (index >= result.snapshots.size())
    throw InputError("render: snapshot " + std::to_string(index) +
                     " does not exist (the result has " + std::to_string(result.snapshots.size()) +
                     ")");
  if (options.width < 200 || options.width > 20000)
    throw InputError("render: width " + std::to_string(options.width) +
                     " px is out of range (200 to 20000)");
  if (!std::isfinite(options.exaggeration))
    throw InputError("render: the exaggeration must be a finite number");
  if (options.exaggeration < 0 &&
      !(std::isfinite(result.scene.exaggeration) && result.scene.exaggeration >= 0))
    throw InputError("render: the scene's exaggeration must be a finite number >= 0");
  if (result.scene.dim != 2 && result.scene.dim != 3)
    throw InputError("render: dim is " + std::to_string(result.scene.dim) + ", not 2 or 3");
  const std::size_t nodes = result.node_count();
  if (nodes == 0 || result.positions.size() % 3 != 0)
    throw InputError("render: the result has " + std::to_string(result.positions.size()) +
                     " position values; need 3 per node and at least one node");
  if (result.bonds.size() % 2 != 0)
    throw InputError("render: the bond list has an odd number of node indices");
  for (std::int64_t node : result.bonds)
    if (node < 0 || static_cast<std::size_t>(node) >= nodes)
      throw InputError("render: a bond names node " + std::to_string(node) + " of " +
                       std::to_string(nodes));
  const Snapshot& snapshot = result.snapshots[index];
  if (snapshot.displacement.size() != 3 * nodes)
    throw InputError("render: snapshot " + std::to_string(index) + " has " +
                     std::to_string(snapshot.displacement.size()) + " displacement values for " +
                     std::to_string(nodes) + " nodes");
  if (snapshot.bond_intact.size() != result.bonds.size() / 2)
    throw InputError("render: snapshot " + std::to_string(index) + " has " +
                     std::to_string(snapshot.bond_intact.size()) + " bond_intact values for " +
                     std::to_string(result.bonds.size() / 2) + " bonds");
}

double reference_length(const RunResult& result, std::size_t bond) {
  const double* a = &result.positions[3 * result.bonds[2 * bond]];
  const double* b = &result.positions[3 * result.bonds[2 * bond + 1]];
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// The node spacing in m: the scene's, or else the shortest bond's reference length.
double node_spacing(const RunResult& result) {
  if (result.scene.spacing > 0) return result.scene.spacing;
  double shortest = std::numeric_limits<double>::infinity();
  for (std::size_t bond = 0; bond < result.bonds.size() / 2; ++bond) {
    const double length = reference_length(result, bond);
    if (length > 0) shortest = std::min(shortest, length);
  }
  return std::isfinite(shortest) ? shortest : 1.0;
}

// All nodes of a 2-D result. Of a 3-D result, the lattice layer nearest the middle of y:
// the nodes whose reference y is within spacing/2 of the node y closest to the mid-width.
std::vector<std::size_t> section_nodes(const RunResult& result, double spacing) {
  const std::size_t nodes = result.node_count();
  std::vector<std::size_t> section;
  section.reserve(nodes);
  if (result.scene.dim == 2) {
    for (std::size_t node = 0; node < nodes; ++node) section.push_back(node);
    return section;
  }
  double y_min = std::numeric_limits<double>::infinity();
  double y_max = -y_min;
  for (std::size_t node = 0; node < nodes; ++node) {
    y_min = std::min(y_min, result.positions[3 * node + 1]);
    y_max = std::max(y_max, result.positions[3 * node + 1]);
  }
  const double mid = 0.5 * (y_min + y_max);
  double layer_y = y_min;
  for (std::size_t node = 0; node < nodes; ++node) {
    const double y = result.positions[3 * node + 1];
    if (std::abs(y - mid) < std::abs(layer_y - mid)) layer_y = y;
  }
  for (std::size_t node = 0; node < nodes; ++node)
    if (std::abs(result.positions[3 * node + 1] - layer_y) < 0.5 * spacing) section.push_back(node);
  return section;
}

std::vector<bool> touches_broken_bond(const RunResult& result, const Snapshot& snapshot) {
  std::vector<bool> touches(result.node_count(), false);
  for (std::size_t bond = 0; bond < snapshot.bond_intact.size(); ++bond) {
    if (snapshot.bond_intact[bond] != 0) continue;
    touches[result.bonds[2 * bond]] = true;
    touches[result.bonds[2 * bond + 1]] = true;
  }
  return touches;
}

struct SectionPoint {
  double x = 0, z = 0;  // deformed position, m
  bool broken = false;
};

std::vector<SectionPoint> section_points(const RunResult& result, const Snapshot& snapshot,
                                         const std::vector<std::size_t>& section,
                                         double exaggeration) {
  const std::vector<bool> broken = touches_broken_bond(result, snapshot);
  std::vector<SectionPoint> points;
  points.reserve(section.size());
  for (std::size_t node : section)
    points.push_back(
        {result.positions[3 * node] + exaggeration * snapshot.displacement[3 * node],
         result.positions[3 * node + 2] + exaggeration * snapshot.displacement[3 * node + 2],
         broken[node]});
  return points;
}

// The data window: reference and deformed positions of the section, padded so dots stay
// inside the frame.
SectionWindow section_window(const RunResult& result, const std::vector<std::size_t>& section,
                             const std::vector<SectionPoint>& points, double spacing) {
  SectionWindow window{
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  auto include = [&window](double x, double z) {
    window.x_min = std::min(window.x_min, x);
    window.x_max = std::max(window.x_max, x);
    window.z_min = std::min(window.z_min, z);
    window.z_max = std::max(window.z_max, z);
  };
  for (std::size_t i = 0; i < section.size(); ++i) {
    include(result.positions[3 * section[i]], result.positions[3 * section[i] + 2]);
    include(points[i].x, points[i].z);
  }
  if (!(std::isfinite(window.x_min) && std::isfinite(window.x_max) && std::isfinite(window.z_min) &&
        std::isfinite(window.z_max)))
    throw InputError("render: the deformed positions are not finite numbers");
  const double pad =
      std::max(spacing, 0.01 * std::max(window.x_max - window.x_min, window.z_max - window.z_min));
  window.x_min -= pad;
  window.x_max += pad;
  window.z_min -= pad;
  window.z_max += pad;
  return window;
}

std::string title_text(const RunResult& result, const Snapshot& snapshot, double exaggeration) {
  char numbers[128];
  std::snprintf(numbers, sizeof numbers, "lambda = %#.4g   exaggeration x%g", snapshot.lambda,
                exaggeration);
  std::string title;
  if (!result.scene.name.empty()) title += result.scene.name + "   ";
  title += result.scene.criterion.empty() ? "elastic" : result.scene.criterion;
  return title + "   " + numbers;
}

// The radius of a particle's dot, pixels, for a spacing of `spacing` pixels. Dots 10 px
// apart or more have radius 0.45 spacing, so each particle shows, with a gap of at least
// 1 px at every bond: every pixel row or column across the gap has a pixel centre in it.
// Closer dots cannot keep such a gap, and a gap under a pixel wide shows or not depending
// on where the pixel centres fall: at 500 m spacing, 800 px wide, the gaps between two
// rows fell on the same pixel rows and made white lines that looked like horizontal
// cracks. So closer dots are drawn solid: radius 0.6 spacing + 0.5 px covers the centre
// of every triangle of neighbours (0.577 spacing away), with room for 4 % stretch, so
// only opened bonds leave white.
double particle_radius(double spacing) {
  return spacing >= 10 ? 0.45 * spacing : std::max(1.0, 0.6 * spacing + 0.5);
}

void draw_points(Canvas& canvas, const SectionLayout& layout,
                 const std::vector<SectionPoint>& points, double spacing) {
  const double pixels_per_m = std::min(layout.x.pixels_per_unit(), layout.z.pixels_per_unit());
  const double radius = particle_radius(spacing * pixels_per_m);
  for (bool broken : {false, true})
    for (const SectionPoint& point : points)
      if (point.broken == broken)
        canvas.disc(layout.x.position(point.x), layout.z.position(point.z), radius,
                    broken ? broken_red : node_grey);
}

}  // namespace

std::size_t snapshot_nearest(const RunResult& result, double lambda) {
  if (result.snapshots.empty()) throw InputError("render: the result has no snapshots");
  if (std::isnan(lambda)) return result.snapshots.size() - 1;
  std::size_t nearest = 0;
  for (std::size_t i = 1; i < result.snapshots.size(); ++i)
    if (std::abs(result.snapshots[i].lambda - lambda) <
        std::abs(result.snapshots[nearest].lambda - lambda))
      nearest = i;
  return nearest;
}

void render_png(const RunResult& result, std::size_t index, const std::string& png_path,
                const RenderOptions& options) {
  check_result(result, index, options);
  const Snapshot& snapshot = result.snapshots[index];
  const double exaggeration =
      options.exaggeration >= 0 ? options.exaggeration : result.scene.exaggeration;
  const double spacing = node_spacing(result);
  const std::vector<std::size_t> section = section_nodes(result, spacing);
  const std::vector<SectionPoint> points = section_points(result, snapshot, section, exaggeration);
  const SectionLayout layout =
      layout_section(section_window(result, section, points, spacing), options.width);

  Canvas canvas(layout.width, layout.height, background);
  draw_axes(canvas, layout, title_text(result, snapshot, exaggeration));
  draw_points(canvas, layout, points, spacing);
  canvas.write_png(png_path);
}

}  // namespace latfrac
