// Fault analysis: clusters of broken bonds, their fitted lines or planes, and grabens.
#include "latfrac/analysis/fault_analysis.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "cluster_split.h"
#include "fault_fit.h"
#include "fault_roles.h"
#include "grabens.h"
#include "latfrac/base/error.h"
#include "point_links.h"

namespace latfrac {

namespace {

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
  if (!(options.wall_distance_spacings >= 0)) {
    throw InputError("fault analysis: the wall distance must be 0 or more (spacings)");
  }
  if (!(options.wall_share > 0 && options.wall_share <= 1)) {
    throw InputError("fault analysis: the wall share must be above 0 and at most 1");
  }
  if (!(options.min_offset >= 0) || !std::isfinite(options.min_offset)) {
    throw InputError("fault analysis: the least offset must be 0 or more (m) and finite");
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

// A broken bond analysed: its reference vector X_j - X_i and its relative displacement
// u_j - u_i at the snapshot, m.
struct BondMotion {
  Point reference = Point::Zero(), relative = Point::Zero();
};

// The fault's offsets (Fault::opening, slip, dip_slip, motion_share) from its bonds'
// motions; `total`: the relative motion over every bond analysed, m.
void set_offsets(Fault& fault, const std::vector<BondMotion>& motions, double total) {
  if (motions.empty()) return;
  const Point normal(fault.normal[0], fault.normal[1], fault.normal[2]);
  // Down the dip: -e_z projected on the fault (undefined for a horizontal one).
  const Point down = (Point(0, 0, -1) + normal.z() * normal).normalized();
  double opening = 0, slip = 0, dip_slip = 0, motion = 0;
  for (const BondMotion& m : motions) {
    // The node on the normal's side less the other.
    const Point across = m.reference.dot(normal) < 0 ? Point(-m.relative) : m.relative;
    const double normal_part = across.dot(normal);
    opening += normal_part;
    slip += (across - normal_part * normal).norm();
    dip_slip += across.dot(down);
    motion += m.relative.norm();
  }
  const double count = static_cast<double>(motions.size());
  fault.opening = opening / count;
  fault.slip = slip / count;
  fault.dip_slip =
      fault.dip_direction == 0 ? std::numeric_limits<double>::quiet_NaN() : dip_slip / count;
  fault.motion_share = total > 0 ? motion / total : 0;
}

// The break mode of each bond from its first event: 0 tensile, 1 shear, 2 pre-cut, -1 none.
std::vector<std::int8_t> break_modes(const RunResult& result) {
  std::vector<std::int8_t> modes(result.bonds.size() / 2, -1);
  for (const BreakEvent& event : result.events) {
    if (modes[event.bond] == -1) modes[event.bond] = static_cast<int>(event.mode);
  }
  return modes;
}

// The bounding box of the nodes' reference positions, m.
struct Box {
  Point low = Point::Zero(), high = Point::Zero();
};

Box lattice_box(const RunResult& result) {
  const std::size_t nodes = result.positions.size() / 3;
  if (nodes == 0) return {};
  Box box{node_position(result, 0), node_position(result, 0)};
  for (std::size_t i = 1; i < nodes; ++i) {
    box.low = box.low.cwiseMin(node_position(result, static_cast<std::int64_t>(i)));
    box.high = box.high.cwiseMax(node_position(result, static_cast<std::int64_t>(i)));
  }
  return box;
}

}  // namespace

const char* to_string(FaultRole role) {
  switch (role) {
    case FaultRole::graben:
      return "graben";
    case FaultRole::precut:
      return "precut";
    case FaultRole::wall:
      return "wall";
    case FaultRole::other:
      return "other";
  }
  return "?";
}

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
  report.min_offset = options.min_offset;
  std::vector<std::int64_t> broken;  // the bonds analysed
  std::vector<BondMotion> motions;
  std::vector<Point> midpoints, precut_midpoints;
  for (std::size_t b = 0; b < snapshot.bond_intact.size(); ++b) {
    if (snapshot.bond_intact[b] != 0) continue;
    const std::int64_t i = result.bonds[2 * b], j = result.bonds[2 * b + 1];
    Point midpoint = 0.5 * (node_position(result, i) + node_position(result, j));
    if (dim == 2) midpoint.y() = 0;
    if (modes[b] == 2) {
      precut_midpoints.push_back(midpoint);
      continue;
    }
    ++report.broken_bonds;
    const std::array<double, 3> offset = result.bond_offset(snapshot, b);
    const BondMotion motion{node_position(result, j) - node_position(result, i),
                            Point(offset[0], offset[1], offset[2])};
    if (!(motion.relative.norm() >= options.min_offset)) continue;
    broken.push_back(static_cast<std::int64_t>(b));
    motions.push_back(motion);
    midpoints.push_back(midpoint);
    report.relative_motion += motion.relative.norm();
  }
  report.moved_bonds = static_cast<std::int64_t>(broken.size());
  report.precut_bonds = static_cast<std::int64_t>(precut_midpoints.size());

  const double spacing = result.scene.spacing;  // m
  const double link = options.link_distance_spacings * spacing;
  const LinkGrid grid(midpoints, link);
  const Box box = lattice_box(result);
  const FaultFitter fitter(dim, options, spacing, box.high - box.low);
  for (const std::vector<std::size_t>& cluster :
       link_components(grid, std::vector<int>(midpoints.size(), 0))) {
    if (static_cast<std::int64_t>(cluster.size()) < options.min_bonds) continue;
    for (const std::vector<std::size_t>& part :
         split_cluster(midpoints, cluster, fitter, options, spacing)) {
      std::vector<Point> points;
      std::vector<BondMotion> part_motions;
      points.reserve(part.size());
      part_motions.reserve(part.size());
      std::int64_t tensile = 0, shear = 0;
      for (const std::size_t k : part) {
        points.push_back(midpoints[k]);
        part_motions.push_back(motions[k]);
        tensile += modes[broken[k]] == 0;
        shear += modes[broken[k]] == 1;
      }
      Fault fault = fitter.fit(points);
      set_offsets(fault, part_motions, report.relative_motion);
      fault.tensile_share = static_cast<double>(tensile) / static_cast<double>(part.size());
      fault.shear_share = static_cast<double>(shear) / static_cast<double>(part.size());
      fault.wall_share =
          wall_share(points, box.low.x(), box.high.x(), options.wall_distance_spacings * spacing);
      fault.precut_distance = precut_distance(points, precut_midpoints);
      report.faults.push_back(fault);
    }
  }
  std::sort(report.faults.begin(), report.faults.end(), [](const Fault& a, const Fault& b) {
    if (a.bonds != b.bonds) return a.bonds > b.bonds;
    return a.centroid < b.centroid;
  });
  report.grabens = find_grabens(result, snapshot, report.faults, options);
  assign_roles(report, options, link);
  return report;
}

}  // namespace latfrac
