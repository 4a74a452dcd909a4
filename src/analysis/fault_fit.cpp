// The line (2-D) or plane (3-D) fitted to a cluster of broken bonds, and whether it is a fault.
#include "fault_fit.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cstdint>
#include <limits>

namespace latfrac {

namespace {

// A dip within this of 0 or 90 deg has no dip direction.
constexpr double kLevelToleranceDeg = 1.0;

double range_along(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& axis) {
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const Eigen::Vector3d& p : points) {
    low = std::min(low, p.dot(axis));
    high = std::max(high, p.dot(axis));
  }
  return high - low;
}

}  // namespace

void set_axes(PrincipalAxes& principal, const Eigen::Matrix3d& covariance, int dim) {
  if (dim == 2) {
    Eigen::Matrix2d xz;
    xz << covariance(0, 0), covariance(0, 2), covariance(2, 0), covariance(2, 2);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(xz);
    for (int i = 0; i < 2; ++i) {
      principal.axes.emplace_back(eigen.eigenvectors()(0, i), 0, eigen.eigenvectors()(1, i));
      principal.variances.push_back(eigen.eigenvalues()(i));
    }
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    for (int i = 0; i < 3; ++i) {
      principal.axes.emplace_back(eigen.eigenvectors().col(i));
      principal.variances.push_back(eigen.eigenvalues()(i));
    }
  }
}

FaultFitter::FaultFitter(int dim, const FaultOptions& options, double spacing,
                         const Eigen::Vector3d& lattice_size)
    : dim_(dim),
      diffuse_variance_ratio_(options.diffuse_variance_ratio),
      diffuse_rms_(options.diffuse_rms_spacings * spacing),
      diffuse_fill_share_(options.diffuse_fill_share),
      lattice_size_(lattice_size) {}

Fault FaultFitter::fit(const std::vector<Eigen::Vector3d>& points) const {
  const PrincipalAxes principal = principal_axes(points, dim_, [](std::size_t) { return true; });
  Fault fault;
  fault.bonds = static_cast<std::int64_t>(points.size());
  // 2-D: second / first variance; 3-D: smallest / middle. Both are variances[0] / [1].
  const double reference = principal.variances[1];
  fault.variance_ratio = reference > 0 ? std::max(principal.variances[0], 0.0) / reference : 1.0;
  fault.extent =
      dim_ == 2 ? range_along(points, principal.axes[1])
                : range_along(points, principal.axes[1]) * range_along(points, principal.axes[2]);
  Eigen::Vector3d normal = principal.axes[0];
  if (normal.z() < 0 || (normal.z() == 0 && normal.x() < 0)) normal = -normal;
  normal.normalize();

  double squared_distance = 0;
  for (const Eigen::Vector3d& p : points)
    squared_distance += std::pow((p - principal.centroid).dot(normal), 2);
  fault.fit_rms = std::sqrt(squared_distance / static_cast<double>(points.size()));
  fault.centroid = {principal.centroid.x(), principal.centroid.y(), principal.centroid.z()};
  fault.normal = {normal.x(), normal.y(), normal.z()};

  // The plane tilts its upward normal towards the side it descends to. The dip direction
  // along x is read from the trace in the x-z section, whose dip is atan(|nx| / nz).
  fault.dip_deg = std::atan2(std::hypot(normal.x(), normal.y()), normal.z()) / kDegree;
  fault.alpha_deg = 90.0 - fault.dip_deg;
  const double trace_dip_deg = std::atan2(std::abs(normal.x()), normal.z()) / kDegree;
  const bool level = fault.dip_deg < kLevelToleranceDeg ||
                     fault.dip_deg > 90.0 - kLevelToleranceDeg ||
                     trace_dip_deg < kLevelToleranceDeg;
  fault.dip_direction = level ? 0 : (normal.x() > 0 ? 1 : -1);
  // A fault cuts across the lattice, so it is thin compared with the lattice's width along
  // its normal. A cluster that fills that width is flat only because the lattice is, such as
  // a shattered slab thin in y whose fit is the slab's mid-plane (normal along y). The
  // cluster's thickness is sqrt(12) rms, the width of an evenly filled band of that rms; the
  // lattice's width is that of its bounding box along the normal, sum |n_i| L_i.
  const double thickness = std::sqrt(12.0) * fault.fit_rms;           // m
  const double lattice_width = normal.cwiseAbs().dot(lattice_size_);  // m
  fault.fill_share = lattice_width > 0 ? thickness / lattice_width : 0.0;
  const bool fills_lattice = fault.fill_share > diffuse_fill_share_;
  fault.diffuse = !(fault.variance_ratio <= diffuse_variance_ratio_) ||
                  fault.fit_rms > diffuse_rms_ || fills_lattice;
  return fault;
}

}  // namespace latfrac
