// Fault analysis: clusters of broken bonds, their fitted lines or planes, and grabens.
#include "latfrac/analysis/fault_analysis.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "cluster_split.h"
#include "fault_fit.h"
#include "latfrac/base/error.h"
#include "point_links.h"

namespace latfrac {

namespace {

// Faults that may bound a graben: inclined, neither near vertical nor near horizontal.
constexpr double kGrabenMinDipDeg = 20.0;
constexpr double kGrabenMaxDipDeg = 80.0;

using Point = Eigen::Vector3d;

void check_input(const RunResult& result, std::size_t index, const FaultOptions& options) {
  if (result.snapshots.empty()) throw InputError("the result has no snapshots: nothing to analyse");
  if (index >= result.snapshots.size()) {
    throw InputError("snapshot " + std::to_string(index) + " is out of range: the result has " +
                     std::to_string(result.snapshots.size()) + " snapshots (0 .. " +
                     std::to_string(result.snapshots.size() - 1) + ")");
  }
  if (result.scene.dim != 2 && result.scene.dim != 3) {
    throw InputError("the result's scene dimension is " + std::to_string(result.scene.dim) +
                     "; fault analysis needs 2 or 3");
  }
  if (!(result.scene.spacing > 0)) throw InputError("the result's lattice spacing is not positive");
  if (!(options.link_distance_spacings > 0)) {
    throw InputError("fault analysis: the link distance must be positive (spacings)");
  }
  if (options.min_bonds < 1) throw InputError("fault analysis: min_bonds must be at least 1");
  if (!(options.diffuse_variance_ratio > 0)) {
    throw InputError("fault analysis: the diffuse variance ratio must be positive");
  }
  if (!(options.diffuse_fill_share > 0)) {
    throw InputError("fault analysis: the diffuse fill share must be positive");
  }
  if (!(options.split_rms_spacings > 0)) {
    throw InputError("fault analysis: the split rms must be positive (spacings)");
  }
  if (options.max_split_depth < 0) {
    throw InputError("fault analysis: max_split_depth must be 0 (never split) or more");
  }
  const std::size_t nodes = result.positions.size() / 3;
  const std::size_t bonds = result.bonds.size() / 2;
  if (result.positions.size() % 3 != 0 || result.bonds.size() % 2 != 0) {
    throw InputError("the result's positions or bonds array has a partial row");
  }
  for (const std::int64_t node : result.bonds) {
    if (node < 0 || static_cast<std::size_t>(node) >= nodes) {
      throw InputError("the result has a bond to node " + std::to_string(node) + " of " +
                       std::to_string(nodes));
    }
  }
  const Snapshot& snapshot = result.snapshots[index];
  if (snapshot.bond_intact.size() != bonds || snapshot.displacement.size() != 3 * nodes) {
    throw InputError("snapshot " + std::to_string(index) + " has " +
                     std::to_string(snapshot.bond_intact.size()) + " bond states and " +
                     std::to_string(snapshot.displacement.size() / 3) + " displacements for " +
                     std::to_string(bonds) + " bonds and " + std::to_string(nodes) + " nodes");
  }
  for (const BreakEvent& event : result.events) {
    if (event.bond < 0 || static_cast<std::size_t>(event.bond) >= bonds) {
      throw InputError("the result has a break event for bond " + std::to_string(event.bond) +
                       " of " + std::to_string(bonds));
    }
  }
}

Point node_position(const RunResult& result, std::int64_t node) {
  return {result.positions[3 * node], result.positions[3 * node + 1],
          result.positions[3 * node + 2]};
}

// The break mode of each bond from its first event: 0 tensile, 1 shear, 2 pre-cut, -1 none.
std::vector<std::int8_t> break_modes(const RunResult& result) {
  std::vector<std::int8_t> modes(result.bonds.size() / 2, -1);
  for (const BreakEvent& event : result.events) {
    if (modes[event.bond] == -1) modes[event.bond] = static_cast<int>(event.mode);
  }
  return modes;
}

// The edges of the bounding box of the nodes' reference positions along x, y, z, m.
Point lattice_size(const RunResult& result) {
  const std::size_t nodes = result.positions.size() / 3;
  if (nodes == 0) return Point::Zero();
  Point low = node_position(result, 0), high = low;
  for (std::size_t i = 1; i < nodes; ++i) {
    low = low.cwiseMin(node_position(result, static_cast<std::int64_t>(i)));
    high = high.cwiseMax(node_position(result, static_cast<std::int64_t>(i)));
  }
  return high - low;
}

// Where the fault's trace in the x-z section at `y` meets the level z.
double trace_x(const Fault& fault, double y, double z) {
  const auto& n = fault.normal;
  const auto& c = fault.centroid;
  return c[0] - (n[1] * (y - c[1]) + n[2] * (z - c[2])) / n[0];
}

bool bounds_graben(const Fault& fault) {
  return !fault.diffuse && fault.dip_direction != 0 && fault.dip_deg >= kGrabenMinDipDeg &&
         fault.dip_deg <= kGrabenMaxDipDeg;
}

// Grabens: neighbouring inclined faults, ordered by where they reach the surface, of which
// the left one descends towards +x and the right one towards -x. Their traces then meet
// below the surface, and both faults must lie above that point. The subsidence compares the
// top-row nodes between the two traces with those outside, leaving out a band of one spacing
// on each side of either trace.
std::vector<Graben> find_grabens(const RunResult& result, const Snapshot& snapshot,
                                 const std::vector<Fault>& faults) {
  const double spacing = result.scene.spacing;
  const std::size_t nodes = result.positions.size() / 3;
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < nodes; ++i) top = std::max(top, result.positions[3 * i + 2]);
  std::vector<std::size_t> surface;
  double mean_y = 0;
  for (std::size_t i = 0; i < nodes; ++i) {
    if (result.positions[3 * i + 2] >= top - spacing / 2) {
      surface.push_back(i);
      mean_y += result.positions[3 * i + 1];
    }
  }
  if (surface.empty()) return {};
  mean_y /= static_cast<double>(surface.size());

  std::vector<std::size_t> candidates;
  for (std::size_t f = 0; f < faults.size(); ++f) {
    if (bounds_graben(faults[f])) candidates.push_back(f);
  }
  std::sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
    return trace_x(faults[a], mean_y, top) < trace_x(faults[b], mean_y, top);
  });

  std::vector<Graben> grabens;
  for (std::size_t k = 0; k + 1 < candidates.size(); ++k) {
    const Fault& left = faults[candidates[k]];
    const Fault& right = faults[candidates[k + 1]];
    if (left.dip_direction != 1 || right.dip_direction != -1) continue;
    Graben graben;
    graben.left_fault = candidates[k];
    graben.right_fault = candidates[k + 1];
    graben.left_surface_x = trace_x(left, mean_y, top);
    graben.right_surface_x = trace_x(right, mean_y, top);
    // Both traces descend inwards, so they meet below the surface at depth d where their
    // horizontal gap closes: gap = d (cot dip_left + cot dip_right) in the x-z section.
    const double closing =
        left.normal[2] / std::abs(left.normal[0]) + right.normal[2] / std::abs(right.normal[0]);
    graben.apex_depth = (graben.right_surface_x - graben.left_surface_x) / closing;
    // The faults must lie above the point where their traces meet. Two faults below it, such
    // as the arms of an inverted V, dip away from each other where they exist: no graben.
    const double apex_z = top - graben.apex_depth;
    if (!(left.centroid[2] > apex_z && right.centroid[2] > apex_z)) continue;

    double inside_sum = 0, outside_sum = 0;
    std::int64_t inside = 0, outside = 0;
    for (const std::size_t i : surface) {
      const double x = result.positions[3 * i];
      const double y = result.positions[3 * i + 1];
      const double z = result.positions[3 * i + 2];
      const double x_left = trace_x(left, y, z);
      const double x_right = trace_x(right, y, z);
      const double uz = snapshot.displacement[3 * i + 2];
      if (x > x_left + spacing && x < x_right - spacing) {
        inside_sum += uz;
        ++inside;
      } else if (x < x_left - spacing || x > x_right + spacing) {
        outside_sum += uz;
        ++outside;
      }
    }
    graben.surface_subsidence = inside > 0 && outside > 0
                                    ? outside_sum / outside - inside_sum / inside
                                    : std::numeric_limits<double>::quiet_NaN();
    grabens.push_back(graben);
  }
  return grabens;
}

}  // namespace

FaultReport analyze_faults(const RunResult& result, std::size_t index,
                           const FaultOptions& options) {
  if (index == kLastSnapshot && !result.snapshots.empty()) index = result.snapshots.size() - 1;
  check_input(result, index, options);
  const Snapshot& snapshot = result.snapshots[index];
  const int dim = result.scene.dim;

  FaultReport report;
  report.dim = dim;
  report.lambda = snapshot.lambda;
  const std::vector<std::int8_t> modes = break_modes(result);
  std::vector<std::int64_t> broken;
  std::vector<Point> midpoints;
  for (std::size_t b = 0; b < snapshot.bond_intact.size(); ++b) {
    if (snapshot.bond_intact[b] != 0 || modes[b] == 2) continue;
    broken.push_back(static_cast<std::int64_t>(b));
    midpoints.push_back(0.5 * (node_position(result, result.bonds[2 * b]) +
                               node_position(result, result.bonds[2 * b + 1])));
    if (dim == 2) midpoints.back().y() = 0;
  }
  report.broken_bonds = static_cast<std::int64_t>(broken.size());

  const double spacing = result.scene.spacing;  // m
  const LinkGrid grid(midpoints, options.link_distance_spacings * spacing);
  const FaultFitter fitter(dim, options, spacing, lattice_size(result));
  for (const std::vector<std::size_t>& cluster :
       link_components(grid, std::vector<int>(midpoints.size(), 0))) {
    if (static_cast<std::int64_t>(cluster.size()) < options.min_bonds) continue;
    for (const std::vector<std::size_t>& part :
         split_cluster(midpoints, cluster, fitter, options, spacing)) {
      std::vector<Point> points;
      points.reserve(part.size());
      std::int64_t tensile = 0, shear = 0;
      for (const std::size_t k : part) {
        points.push_back(midpoints[k]);
        tensile += modes[broken[k]] == 0;
        shear += modes[broken[k]] == 1;
      }
      Fault fault = fitter.fit(points);
      fault.tensile_share = static_cast<double>(tensile) / static_cast<double>(part.size());
      fault.shear_share = static_cast<double>(shear) / static_cast<double>(part.size());
      report.faults.push_back(fault);
    }
  }
  std::sort(report.faults.begin(), report.faults.end(), [](const Fault& a, const Fault& b) {
    if (a.bonds != b.bonds) return a.bonds > b.bonds;
    return a.centroid < b.centroid;
  });
  report.grabens = find_grabens(result, snapshot, report.faults);
  return report;
}

}  // namespace latfrac
