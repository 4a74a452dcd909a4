// Small-kinematics bond law: normal and shear springs on the reference bond direction.
#include "latfrac/bond_law.h"

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

}  // namespace latfrac
