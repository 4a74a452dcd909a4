// The views of a snapshot: which nodes and broken bonds a picture draws, and where.
#include "scene_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "latfrac/base/error.h"

namespace latfrac {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

Vec3 reference_position(const RunResult& result, std::size_t node) {
  return {result.positions[3 * node], result.positions[3 * node + 1],
          result.positions[3 * node + 2]};
}

std::string km(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g km", metres / 1000);
  return text;
}

// The mode of each bond's last break event at or before `lambda` along the loading (-1:
// none). A compression run's lambda falls from 0: its events "before" a snapshot are the
// ones at a larger lambda.
std::vector<std::int8_t> bond_modes(const RunResult& result, double lambda) {
  std::vector<std::int8_t> modes(result.bond_count(), -1);
  const double loading = lambda != 0 ? lambda : result.summary.final_lambda;
  const double sense = loading < 0 ? -1.0 : 1.0;
  for (const BreakEvent& event : result.events)
    if (sense * event.lambda <= sense * lambda && event.bond >= 0 &&
        static_cast<std::size_t>(event.bond) < modes.size())
      modes[event.bond] = static_cast<std::int8_t>(event.mode);
  return modes;
}

// Whether the bond between nodes a and b has its reference midpoint in the view's slab: one
// slab per bond, and no bond seen end-on from far off the section.
bool in_slab(const SceneView& view, const RunResult& result, std::size_t a, std::size_t b) {
  if (view.kind == PictureView::section && result.scene.dim == 2) return true;
  const Vec3 middle{(result.positions[3 * a] + result.positions[3 * b]) / 2,
                    (result.positions[3 * a + 1] + result.positions[3 * b + 1]) / 2,
                    (result.positions[3 * a + 2] + result.positions[3 * b + 2]) / 2};
  return std::abs(dot(middle, view.away) - view.plane) < view.spacing / 2;
}

// The nodes whose reference coordinate `axis` lies within half a spacing of the node layer
// nearest `at`. Throws InputError when `at` lies outside the nodes' range by more than that.
std::vector<bool> slab(const RunResult& result, int axis, double at, double spacing,
                       const std::string& name, double& layer) {
  const std::size_t nodes = result.node_count();
  double low = infinity, high = -infinity;
  for (std::size_t node = 0; node < nodes; ++node) {
    low = std::min(low, result.positions[3 * node + axis]);
    high = std::max(high, result.positions[3 * node + axis]);
  }
  if (!(at >= low - spacing / 2 && at <= high + spacing / 2)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "render: the section %s = %g m is outside the block (%s from %g to %g m)",
                  name.c_str(), at, name.c_str(), low, high);
    throw InputError(text);
  }
  layer = low;
  for (std::size_t node = 0; node < nodes; ++node)
    if (std::abs(result.positions[3 * node + axis] - at) < std::abs(layer - at))
      layer = result.positions[3 * node + axis];
  std::vector<bool> inside(nodes);
  for (std::size_t node = 0; node < nodes; ++node)
    inside[node] = std::abs(result.positions[3 * node + axis] - layer) < spacing / 2;
  return inside;
}

void orient(SceneView& view, const RunResult& result, const PictureOptions& options) {
  switch (view.kind) {
    case PictureView::section:
      if (result.scene.dim == 3 && options.section_axis == SectionAxis::x) {
        view.right = {0, 1, 0}, view.up = {0, 0, 1}, view.away = {-1, 0, 0};
        view.h_title = "y (km)";
      } else {
        view.right = {1, 0, 0}, view.up = {0, 0, 1}, view.away = {0, 1, 0};
        view.h_title = "x (km)";
      }
      view.v_title = "z (km)";
      break;
    case PictureView::map:
      view.right = {1, 0, 0}, view.up = {0, 1, 0}, view.away = {0, 0, -1};
      view.h_title = "x (km)", view.v_title = "y (km)";
      view.where = "map of the surface";
      break;
    case PictureView::oblique: {
      // Turned 20 degrees about z from the x axis, looking 25 degrees down.
      const double turn = 20 * std::numbers::pi / 180, tilt = 25 * std::numbers::pi / 180;
      const Vec3 forward{-std::sin(turn), std::cos(turn), 0};
      view.right = {std::cos(turn), std::sin(turn), 0};
      view.up = {forward[0] * std::sin(tilt), forward[1] * std::sin(tilt), std::cos(tilt)};
      view.away = {forward[0] * std::cos(tilt), forward[1] * std::cos(tilt), -std::sin(tilt)};
      view.where = "oblique view";
      break;
    }
  }
}

// Which nodes the view draws: a 2-D run's every node, a 3-D block's slab (sets view.plane).
std::vector<bool> drawn_nodes(SceneView& view, const RunResult& result,
                              const PictureOptions& options) {
  const std::size_t nodes = result.node_count();
  if (view.kind == PictureView::section && result.scene.dim == 2) return std::vector(nodes, true);
  if (view.kind == PictureView::section) {
    const int axis = options.section_axis == SectionAxis::x ? 0 : 1;
    const char* name = axis == 0 ? "x" : "y";
    double at = 0;
    if (options.section_at) {
      at = *options.section_at;
    } else {
      double low = infinity, high = -infinity;
      for (std::size_t node = 0; node < nodes; ++node) {
        low = std::min(low, result.positions[3 * node + axis]);
        high = std::max(high, result.positions[3 * node + axis]);
      }
      at = 0.5 * (low + high);
    }
    view.where = std::string("section ") + name + " = " + km(at);
    double layer = 0;
    std::vector<bool> inside = slab(result, axis, at, view.spacing, name, layer);
    view.plane = axis == 0 ? -layer : layer;
    return inside;
  }
  double top = -infinity;
  for (std::size_t node = 0; node < nodes; ++node)
    top = std::max(top, result.positions[3 * node + 2]);
  double layer = 0;
  std::vector<bool> inside = slab(result, 2, top, view.spacing, "z", layer);
  view.plane = -layer;
  return inside;
}

void fit_window(SceneView& view, const RunResult& result, const Snapshot& snapshot,
                const std::vector<bool>& drawn) {
  double h_min = infinity, h_max = -infinity, v_min = infinity, v_max = -infinity;
  auto include = [&](const ViewPoint& p) {
    h_min = std::min(h_min, p.h), h_max = std::max(h_max, p.h);
    v_min = std::min(v_min, p.v), v_max = std::max(v_max, p.v);
  };
  const bool everything = view.kind == PictureView::oblique;
  for (std::size_t node = 0; node < result.node_count(); ++node) {
    if (!everything && !drawn[node]) continue;
    include(view.project(reference_position(result, node)));
    include(view.project(deformed_position(result, snapshot, node, view.exaggeration)));
  }
  for (const ViewBond& bond : view.broken) include(bond.from), include(bond.to);
  if (!(std::isfinite(h_min) && std::isfinite(h_max) && std::isfinite(v_min) &&
        std::isfinite(v_max)))
    throw InputError("render: the deformed positions are not finite numbers");
  // The oblique view leaves room round the block for its edges' tick labels.
  const double share = view.kind == PictureView::oblique ? 0.08 : 0.01;
  const double pad = std::max(0.6 * view.spacing, share * std::max(h_max - h_min, v_max - v_min));
  view.h_min = h_min - pad, view.h_max = h_max + pad;
  view.v_min = v_min - pad, view.v_max = v_max + pad;
}

}  // namespace

Vec3 deformed_position(const RunResult& result, const Snapshot& snapshot, std::size_t node,
                       double exaggeration) {
  Vec3 p = reference_position(result, node);
  for (int axis = 0; axis < 3; ++axis)
    p[axis] += exaggeration * snapshot.displacement[3 * node + axis];
  return p;
}

double node_spacing(const RunResult& result) {
  if (result.scene.spacing > 0) return result.scene.spacing;
  double shortest = infinity;
  for (std::size_t bond = 0; bond < result.bond_count(); ++bond) {
    const Vec3 a = reference_position(result, result.bonds[2 * bond]);
    const Vec3 b = reference_position(result, result.bonds[2 * bond + 1]);
    const double length = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    if (length > 0) shortest = std::min(shortest, length);
  }
  return std::isfinite(shortest) ? shortest : 1.0;
}

SceneView make_view(const RunResult& result, const Snapshot& snapshot,
                    const PictureOptions& options, double exaggeration) {
  SceneView view;
  view.kind = options.view;
  if (view.kind != PictureView::section && result.scene.dim != 3)
    throw InputError("render: a " + std::string(name_of(view.kind)) +
                     " view needs a 3-D result; this one is 2-D (use --view section)");
  if (result.scene.dim == 2 && options.section_at)
    throw InputError(
        "render: a 2-D result is one x-z section; --section-y and --section-x "
        "apply to 3-D results");
  if (view.kind != PictureView::section && options.section_at)
    throw InputError("render: --section-y and --section-x choose the plane of a section view; "
                     "the " + std::string(name_of(view.kind)) +
                     " view draws the whole block (use --view section, or leave them out)");
  view.spacing = node_spacing(result);
  view.exaggeration = exaggeration;
  orient(view, result, options);
  const std::vector<bool> drawn = drawn_nodes(view, result, options);

  const std::size_t nodes = result.node_count();
  view.box_low = {infinity, infinity, infinity};
  view.box_high = {-infinity, -infinity, -infinity};
  std::vector<Vec3> deformed(nodes);
  for (std::size_t node = 0; node < nodes; ++node) {
    deformed[node] = deformed_position(result, snapshot, node, exaggeration);
    for (int axis = 0; axis < 3; ++axis) {
      view.box_low[axis] = std::min(view.box_low[axis], deformed[node][axis]);
      view.box_high[axis] = std::max(view.box_high[axis], deformed[node][axis]);
    }
    if (drawn[node]) view.nodes.push_back({node, view.project(deformed[node])});
  }

  const std::vector<std::int8_t> modes = bond_modes(result, snapshot.lambda);
  view.min_offset = options.min_offset;
  view.touches_broken.assign(nodes, false);
  for (std::size_t bond = 0; bond < result.bond_count(); ++bond) {
    if (snapshot.bond_intact[bond] != 0) continue;
    const std::size_t a = result.bonds[2 * bond], b = result.bonds[2 * bond + 1];
    if (options.min_offset > 0) {
      const auto [dx, dy, dz] = result.bond_offset(snapshot, bond);
      if (!(std::hypot(dx, dy, dz) >= options.min_offset)) continue;
    }
    view.touches_broken[a] = view.touches_broken[b] = true;
    if (view.kind != PictureView::oblique && !in_slab(view, result, a, b)) continue;
    const Vec3 middle{(deformed[a][0] + deformed[b][0]) / 2, (deformed[a][1] + deformed[b][1]) / 2,
                      (deformed[a][2] + deformed[b][2]) / 2};
    view.broken.push_back({bond, view.project(deformed[a]), view.project(deformed[b]),
                           view.depth(middle), modes[bond]});
  }
  if (view.kind == PictureView::oblique)
    std::stable_sort(view.broken.begin(), view.broken.end(),
                     [](const ViewBond& p, const ViewBond& q) { return p.depth > q.depth; });
  fit_window(view, result, snapshot, drawn);
  return view;
}

}  // namespace latfrac
