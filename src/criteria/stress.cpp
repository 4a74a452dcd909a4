// Resolution of a stress tensor on a plane, and its invariants.
#include "latfrac/criteria/stress.h"

namespace latfrac {

Eigen::Matrix3d stress_matrix(const VoigtStress& s) {
  Eigen::Matrix3d m;
  m << s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2];
  return m;
}

ResolvedStress resolve_on(const VoigtStress& s, const Eigen::Vector3d& n) {
  // Voigt xx, yy, zz, yz, xz, xy.
  const Eigen::Vector3d traction(s[0] * n.x() + s[5] * n.y() + s[4] * n.z(),
                                 s[5] * n.x() + s[1] * n.y() + s[3] * n.z(),
                                 s[4] * n.x() + s[3] * n.y() + s[2] * n.z());
  ResolvedStress r;
  r.normal = n.dot(traction);
  r.shear = traction - r.normal * n;
  return r;
}

double first_invariant(const VoigtStress& s) { return s[0] + s[1] + s[2]; }

double j2_product(const VoigtStress& a, const VoigtStress& b) {
  const double normal =
      (a[0] - a[1]) * (b[0] - b[1]) + (a[1] - a[2]) * (b[1] - b[2]) + (a[2] - a[0]) * (b[2] - b[0]);
  return normal / 6 + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
}

}  // namespace latfrac
