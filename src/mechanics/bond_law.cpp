// Bond laws: normal and shear springs on the reference (small) or current (large) direction.
#include "latfrac/mechanics/bond_law.h"

#include <Eigen/Geometry>
#include <cmath>

namespace latfrac {

// kn along n0; ks along the in-plane perpendicular (2-D) or two perpendiculars (3-D).
std::vector<RankOneTerm> BondLaw::stiffness_terms(const PairSprings& pair, PairState) const {
  const Vec3& n0 = pair.direction;
  std::vector<RankOneTerm> terms{{pair.kn, n0}};
  if (dim_ == 2) {
    terms.push_back({pair.ks, Vec3(-n0.z(), 0, n0.x())});
  } else {
    const Vec3 helper = std::abs(n0.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 first = n0.cross(helper).normalized();
    terms.push_back({pair.ks, first});
    terms.push_back({pair.ks, n0.cross(first)});
  }
  return terms;
}

BondDeformation SmallKinematics::deformation(const BondReference& reference,
                                             const Vec3& relative_displacement) const {
  BondDeformation d;
  d.normal = reference.direction.dot(relative_displacement);
  d.shear = relative_displacement - d.normal * reference.direction;
  return d;
}

Mat3 SmallKinematics::tangent(const PairSprings& pair, PairState, const Vec3&) const {
  const Mat3 projector = pair.direction * pair.direction.transpose();
  return pair.kn * projector + pair.ks * (Mat3::Identity() - projector);
}

namespace {

// The current bond vector d = L0 n0 + du, its length r and direction n.
struct CurrentBond {
  Vec3 direction;
  double length;
};

CurrentBond current_bond(const Vec3& direction, double length, const Vec3& relative_displacement) {
  const Vec3 d = length * direction + relative_displacement;
  const double r = d.norm();
  if (!(r > 0)) return {direction, 0.0};
  return {d / r, r};
}

}  // namespace

BondDeformation LargeKinematics::deformation(const BondReference& reference,
                                             const Vec3& relative_displacement) const {
  const CurrentBond current =
      current_bond(reference.direction, reference.length, relative_displacement);
  BondDeformation d;
  d.normal = current.direction.dot(relative_displacement);
  d.shear = relative_displacement - d.normal * current.direction;
  return d;
}

Vec3 LargeKinematics::tension(const PairSprings& pair, PairState, const Vec3& du) const {
  const CurrentBond current = current_bond(pair.direction, pair.length, du);
  const double dn = current.direction.dot(du);
  return pair.ks * du + (pair.kn - pair.ks) * dn * current.direction;
}

// T = ks I + (kn - ks) (n g' + (dn / r) P), P = I - n n', g = n + P du / r (bond_law.h).
Mat3 LargeKinematics::jacobian(const PairSprings& pair, PairState, const Vec3& du) const {
  const CurrentBond current = current_bond(pair.direction, pair.length, du);
  const Vec3& n = current.direction;
  const double kn = pair.kn, ks = pair.ks;
  if (current.length == 0) {
    const Mat3 projector = n * n.transpose();
    return kn * projector + ks * (Mat3::Identity() - projector);
  }
  const Mat3 perpendicular = Mat3::Identity() - n * n.transpose();
  const double dn = n.dot(du);
  const Vec3 normal_gradient = n + perpendicular * du / current.length;
  return ks * Mat3::Identity() +
         (kn - ks) * (n * normal_gradient.transpose() + (dn / current.length) * perpendicular);
}

Mat3 LargeKinematics::tangent(const PairSprings& pair, PairState state, const Vec3& du) const {
  const Mat3 exact = jacobian(pair, state, du);
  return 0.5 * (exact + exact.transpose());
}

}  // namespace latfrac
