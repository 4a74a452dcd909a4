// The roles of a run's faults: the graben's two, the pre-cut fault, the wall faults.
#include "fault_roles.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace latfrac {

double wall_share(const std::vector<Eigen::Vector3d>& points, double x_min, double x_max,
                  double distance) {
  if (points.empty()) return 0;
  const auto near_wall = std::count_if(points.begin(), points.end(), [&](const auto& p) {
    return p.x() - x_min <= distance || x_max - p.x() <= distance;
  });
  return static_cast<double>(near_wall) / static_cast<double>(points.size());
}

double precut_distance(const std::vector<Eigen::Vector3d>& points,
                       const std::vector<Eigen::Vector3d>& precut_midpoints) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points)
    for (const Eigen::Vector3d& cut : precut_midpoints)
      nearest = std::min(nearest, (p - cut).squaredNorm());
  return std::sqrt(nearest);
}

void assign_roles(FaultReport& report, const FaultOptions& options, double link) {
  std::vector<Fault>& faults = report.faults;
  for (Fault& fault : faults)
    fault.role = fault.wall_share >= options.wall_share ? FaultRole::wall : FaultRole::other;

  // The pre-cut fault: the largest fault (not diffuse) that comes within a link of a pre-cut
  // bond; the nearer on a tie, then the first.
  for (std::size_t f = 0; f < faults.size(); ++f) {
    if (faults[f].diffuse || !(faults[f].precut_distance <= link)) continue;
    if (report.precut_fault) {
      const Fault& best = faults[*report.precut_fault];
      if (faults[f].bonds < best.bonds) continue;
      if (faults[f].bonds == best.bonds && faults[f].precut_distance >= best.precut_distance)
        continue;
    }
    report.precut_fault = f;
  }
  if (report.precut_fault) faults[*report.precut_fault].role = FaultRole::precut;

  // The graben: the one whose block subsided most (a NaN subsidence counts least); the first
  // on a tie.
  auto subsided = [](const Graben& g) {
    return std::isnan(g.surface_subsidence) ? -std::numeric_limits<double>::infinity()
                                            : g.surface_subsidence;
  };
  for (std::size_t g = 0; g < report.grabens.size(); ++g) {
    if (!report.graben || subsided(report.grabens[g]) > subsided(report.grabens[*report.graben]))
      report.graben = g;
  }
  if (report.graben) {
    faults[report.grabens[*report.graben].left_fault].role = FaultRole::graben;
    faults[report.grabens[*report.graben].right_fault].role = FaultRole::graben;
  }
}

}  // namespace latfrac
