// The bond law: an intact bond's tension vector and tangent stiffness from its nodes'
// displacements (the interaction law of the intact state, interaction_law.h).
//
// Small kinematics (the default) measures the relative displacement du = u_j - u_i
// against the reference direction n0:
//   dn = n0 . du (tension positive),  ds = du - dn n0,
//   t  = kn dn n0 + ks ds   (the force on node i; node j feels -t)
// which is linear in du, so the tangent is kn n0 n0' + ks (I - n0 n0').
// Every residual and every stiffness matrix in latfrac comes from the pairs' interaction
// laws, so the large-kinematics law (current direction n) replaces this one without
// touching assembly.
//
// Large kinematics (model.md section 2, docs/large-kinematics.md) keeps the same
// relative displacement du = u_j - u_i = (x_j - x_i) - d0 but measures it along the
// current bond direction: with d = d0 + du (d0 = L0 n0), r = |d|, n = d / r,
//   dn = n . du,  ds = du - dn n,  t = kn dn n + ks ds = ks du + (kn - ks) dn n.
// Its tangent, with P = I - n n' and g = d(dn)/d(du) = n + P du / r, is
//   T = ks I + (kn - ks) (n g' + (dn / r) P).
// Since P du = -P d0, the term n g' = n n' - n (P d0)' / r is not symmetric once the bond
// has rotated (P d0 != 0): the law has no stored energy. jacobian() returns T itself;
// tangent(), which the stiffness assembly uses, returns its symmetric part (T + T') / 2.
// The assembly stores the upper triangle of a symmetric matrix (CHOLMOD's stype = 1), so
// what CHOLMOD factorizes is then exactly the symmetric part of the Jacobian of R,
// independent of the node numbering. Mirroring the upper triangle of T instead gives a
// matrix whose bond blocks do not vanish on a rigid translation and is indefinite in 3-D at a
// few per cent strain. With (T + T') / 2, KINSOL's Newton (inexact now, its error of the
// order of the bond rotations) converges in 6-9 iterations from rest at 5-30 % extension
// on the tests' scenes (docs/large-kinematics.md).
// Neither law is invariant under rigid rotation: a rotation by theta gives
// |ds| = L0 |sin theta| in both, and dn = L0 (cos theta - 1) (small) or L0 (1 - cos theta)
// (large).
#pragma once

#include "latfrac/base/linear_algebra.h"
#include "latfrac/mechanics/interaction_law.h"

namespace latfrac {

// Normal and shear displacement of a bond, m.
struct BondDeformation {
  double normal = 0;          // dn, tension positive
  Vec3 shear = Vec3::Zero();  // ds
};

// A bond's reference geometry: unit vector n0 from node i to node j, and length L0 (m).
struct BondReference {
  const Vec3& direction;
  double length;
};

// The law of intact bonds (the state argument is always PairState::intact). Its
// stiffness terms are those at rest: kn n0 n0' + ks (I - n0 n0'), written as kn along n0
// and ks along the perpendiculars in the lattice's plane (2-D) or space (3-D).
class BondLaw : public InteractionLaw {
 public:
  explicit BondLaw(int dim) : dim_(dim) {}
  // relative_displacement = u_j - u_i.
  virtual BondDeformation deformation(const BondReference& reference,
                                      const Vec3& relative_displacement) const = 0;
  std::vector<RankOneTerm> stiffness_terms(const PairSprings& pair, PairState) const override;

 private:
  int dim_;
};

class SmallKinematics final : public BondLaw {
 public:
  using BondLaw::BondLaw;
  BondDeformation deformation(const BondReference& reference,
                              const Vec3& relative_displacement) const override;
  // kn dn n0 + ks (du - dn n0) = ks du + (kn - ks) dn n0. Defined here so that a sweep that
  // knows its law is this one (the class is final) calls it inline.
  Vec3 tension(const PairSprings& pair, PairState, const Vec3& du) const override {
    const double dn = pair.direction.dot(du);
    return pair.ks * du + (pair.kn - pair.ks) * dn * pair.direction;
  }
  Mat3 tangent(const PairSprings& pair, PairState, const Vec3& du) const override;
  bool is_linear() const override { return true; }
};

// jacobian() is the exact T, tangent() its symmetric part (see above). A bond collapsed
// to zero length (r = 0) has no current direction: it falls back to n0.
class LargeKinematics final : public BondLaw {
 public:
  using BondLaw::BondLaw;
  BondDeformation deformation(const BondReference& reference,
                              const Vec3& relative_displacement) const override;
  Vec3 tension(const PairSprings& pair, PairState, const Vec3& du) const override;
  Mat3 tangent(const PairSprings& pair, PairState, const Vec3& du) const override;
  Mat3 jacobian(const PairSprings& pair, PairState, const Vec3& du) const override;
  bool is_linear() const override { return false; }
};

}  // namespace latfrac
