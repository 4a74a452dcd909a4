// Bond laws: normal and shear springs on the reference (small) or current (large) direction.
#include "latfrac/mechanics/bond_law.h"

namespace latfrac {

BondDeformation SmallKinematics::deformation(const BondReference& reference,
                                             const Vec3& relative_displacement) const {
  BondDeformation d;
  d.normal = reference.direction.dot(relative_displacement);
  d.shear = relative_displacement - d.normal * reference.direction;
  return d;
}

// kn dn n0 + ks (du - dn n0) = ks du + (kn - ks) dn n0.
Vec3 SmallKinematics::tension(const BondReference& reference, const Vec3& relative_displacement,
                              double kn, double ks) const {
  const double dn = reference.direction.dot(relative_displacement);
  return ks * relative_displacement + (kn - ks) * dn * reference.direction;
}

Mat3 SmallKinematics::tangent(const BondReference& reference, const Vec3&, double kn,
                              double ks) const {
  const Mat3 projector = reference.direction * reference.direction.transpose();
  return kn * projector + ks * (Mat3::Identity() - projector);
}

namespace {

// The current bond vector d = L0 n0 + du, its length r and direction n.
struct CurrentBond {
  Vec3 direction;
  double length;
};

CurrentBond current_bond(const BondReference& reference, const Vec3& relative_displacement) {
  const Vec3 d = reference.length * reference.direction + relative_displacement;
  const double r = d.norm();
  if (!(r > 0)) return {reference.direction, 0.0};
  return {d / r, r};
}

}  // namespace

BondDeformation LargeKinematics::deformation(const BondReference& reference,
                                             const Vec3& relative_displacement) const {
  const CurrentBond current = current_bond(reference, relative_displacement);
  BondDeformation d;
  d.normal = current.direction.dot(relative_displacement);
  d.shear = relative_displacement - d.normal * current.direction;
  return d;
}

Vec3 LargeKinematics::tension(const BondReference& reference, const Vec3& relative_displacement,
                              double kn, double ks) const {
  const CurrentBond current = current_bond(reference, relative_displacement);
  const double dn = current.direction.dot(relative_displacement);
  return ks * relative_displacement + (kn - ks) * dn * current.direction;
}

// T = ks I + (kn - ks) (n g' + (dn / r) P), P = I - n n', g = n + P du / r (bond_law.h).
Mat3 LargeKinematics::jacobian(const BondReference& reference, const Vec3& relative_displacement,
                               double kn, double ks) const {
  const CurrentBond current = current_bond(reference, relative_displacement);
  const Vec3& n = current.direction;
  if (current.length == 0) {
    const Mat3 projector = n * n.transpose();
    return kn * projector + ks * (Mat3::Identity() - projector);
  }
  const Mat3 perpendicular = Mat3::Identity() - n * n.transpose();
  const double dn = n.dot(relative_displacement);
  const Vec3 normal_gradient = n + perpendicular * relative_displacement / current.length;
  return ks * Mat3::Identity() +
         (kn - ks) * (n * normal_gradient.transpose() + (dn / current.length) * perpendicular);
}

Mat3 LargeKinematics::tangent(const BondReference& reference, const Vec3& relative_displacement,
                              double kn, double ks) const {
  const Mat3 exact = jacobian(reference, relative_displacement, kn, ks);
  return 0.5 * (exact + exact.transpose());
}

}  // namespace latfrac
