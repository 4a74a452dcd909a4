// Small-kinematics bond law: normal and shear springs on the reference bond direction.
#include "latfrac/bond_law.h"

namespace latfrac {

BondDeformation SmallKinematics::deformation(const Vec3& reference_vector,
                                             const Vec3& relative_displacement) const {
  const Vec3 n0 = reference_vector.normalized();
  BondDeformation d;
  d.normal = n0.dot(relative_displacement);
  d.shear = relative_displacement - d.normal * n0;
  return d;
}

Vec3 SmallKinematics::tension(const Vec3& reference_vector, const Vec3& relative_displacement,
                              double kn, double ks) const {
  const BondDeformation d = deformation(reference_vector, relative_displacement);
  return kn * d.normal * reference_vector.normalized() + ks * d.shear;
}

Mat3 SmallKinematics::tangent(const Vec3& reference_vector, const Vec3&, double kn,
                              double ks) const {
  const Vec3 n0 = reference_vector.normalized();
  const Mat3 projector = n0 * n0.transpose();
  return kn * projector + ks * (Mat3::Identity() - projector);
}

}  // namespace latfrac
