// The roles of a run's faults: the graben's two, the pre-cut fault, wall faults.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "latfrac/analysis/fault_analysis.h"

namespace latfrac {

// The share of the points (m) within `distance` (m) of either side wall, x = x_min or x_max.
double wall_share(const std::vector<Eigen::Vector3d>& points, double x_min, double x_max,
                  double distance);

// The smallest distance (m) from the points to the pre-cut bonds' midpoints; +inf when
// there is no pre-cut.
double precut_distance(const std::vector<Eigen::Vector3d>& points,
                       const std::vector<Eigen::Vector3d>& precut_midpoints);

// Sets each fault's role, report.graben and report.precut_fault from the faults' wall shares
// and pre-cut distances and the grabens found. `link` (m) is the clusters' link distance: a
// fault that close to a pre-cut bond would share its cluster.
void assign_roles(FaultReport& report, const FaultOptions& options, double link);

}  // namespace latfrac
