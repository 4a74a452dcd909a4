// The line (2-D) or plane (3-D) fitted to a cluster of broken bonds, and whether it is a fault.
//
// Total least squares: the principal axes of the points' covariance about their centroid.
// It minimises perpendicular distances, so unlike a regression z(x) it treats a vertical
// fault like any other. The line runs along the largest axis; the plane's normal is the
// smallest axis. docs/fault-analysis.md ("Diffuse clusters") gives the rules by which a fit
// is a fault or a shattered region.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

#include "latfrac/analysis/fault_analysis.h"

namespace latfrac {

inline constexpr double kDegree = M_PI / 180.0;  // one degree in radians

// The principal axes of a set of points. In 2-D the points lie in the x-z plane (y = 0) and
// there are two.
struct PrincipalAxes {
  std::size_t count = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> axes;  // unit vectors, smallest variance first
  std::vector<double> variances;      // m^2, ascending
};

// Fills principal.axes and .variances from the points' covariance (m^2) about the centroid.
void set_axes(PrincipalAxes& principal, const Eigen::Matrix3d& covariance, int dim);

// The principal axes of the points k with select(k).
template <class Select>
PrincipalAxes principal_axes(const std::vector<Eigen::Vector3d>& points, int dim, Select&& select) {
  PrincipalAxes principal;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!select(k)) continue;
    principal.centroid += points[k];
    ++principal.count;
  }
  if (principal.count == 0) return principal;
  principal.centroid /= static_cast<double>(principal.count);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!select(k)) continue;
    const Eigen::Vector3d d = points[k] - principal.centroid;
    covariance += d * d.transpose();
  }
  covariance /= static_cast<double>(principal.count);
  set_axes(principal, covariance, dim);
  return principal;
}

// Fits clusters of one run and flags those that are no fault (FaultOptions: the variance
// ratio, the rms and the fill thresholds).
class FaultFitter final {
 public:
  // spacing: the lattice spacing, m. lattice_size: the edges of the bounding box of the
  // lattice's nodes (reference positions) along x, y, z, m.
  FaultFitter(int dim, const FaultOptions& options, double spacing,
              const Eigen::Vector3d& lattice_size);

  int dim() const { return dim_; }

  // The fit of the points (m); tensile_share and shear_share are left at 0.
  Fault fit(const std::vector<Eigen::Vector3d>& points) const;

 private:
  int dim_;
  double diffuse_variance_ratio_;
  double diffuse_rms_;  // m
  double diffuse_fill_share_;
  Eigen::Vector3d lattice_size_;  // m
};

}  // namespace latfrac
