// The plane a broken bond's crack lies in (crack_plane.h).
#include "latfrac/criteria/crack_plane.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

namespace latfrac {

Vec3 crack_plane_normal(const VoigtStress& stress, const Vec3& bond_direction, BreakMode mode,
                        double friction_angle, int dim) {
  Vec3 most_compressive, least_compressive;  // sigma1's and sigma3's directions
  if (dim == 2) {
    const Eigen::Matrix2d s{{stress[0], stress[4]}, {stress[4], stress[2]}};
    if (s(0, 1) == 0 && s(0, 0) == s(1, 1)) return bond_direction;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(s);
    const Eigen::Vector2d a = eigen.eigenvectors().col(0), b = eigen.eigenvectors().col(1);
    most_compressive = {a.x(), 0, a.y()};
    least_compressive = {b.x(), 0, b.y()};
  } else {
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(stress_matrix(stress));
    const Vec3 values = eigen.eigenvalues();
    if (values[2] - values[0] <= 1e-12 * values.cwiseAbs().maxCoeff()) return bond_direction;
    most_compressive = eigen.eigenvectors().col(0);
    least_compressive = eigen.eigenvectors().col(2);
  }
  Vec3 normal;
  if (mode == BreakMode::tensile) {
    normal = least_compressive;
  } else {
    const double beta = std::numbers::pi / 4 + friction_angle / 2;
    const Vec3 one = std::cos(beta) * most_compressive + std::sin(beta) * least_compressive;
    const Vec3 other = std::cos(beta) * most_compressive - std::sin(beta) * least_compressive;
    normal = std::abs(one.dot(bond_direction)) >= std::abs(other.dot(bond_direction)) ? one : other;
  }
  normal.normalize();
  return normal.dot(bond_direction) >= 0 ? normal : Vec3(-normal);
}

}  // namespace latfrac
