// The contact a broken bond leaves, with Coulomb friction (2-D): a compression-only normal
// spring kn, and a tangential spring ks that sticks until its force reaches mu |Fn|, then
// slides.
//
// States (pair_state.h), with dn = n0 . du, the tangent t = n0 turned by 90 degrees in the
// lattice's plane, and the pair's memory (ContactMemory: anchor a, sense of slip s):
//   open:   nothing acts.
//   closed: sticks: t_force = kn dn n0 + ks (P du - a), P = I - n0 n0' (a linear law with
//           a constant term -ks a: the anchored spring is a load).
//   slip:   slides along s: t_force = kn dn n0 + mu kn (-dn) s. Its tangent
//           kn n0 n0' - mu kn s n0' is nonsymmetric; the factor holds kn n0 n0' and the
//           solver adds the rest (coupling_terms; solvers/equilibrium.h).
// Switches (events on an affine path, where every quantity below is affine in lambda):
//   open -> closed   where dn falls through 0; the anchor is set there (a = P du: the
//                    tangential spring starts unstretched);
//   closed -> open   where dn rises through 0;
//   closed -> slip   where ks |t . (du - a)| reaches mu kn (-dn), in the sense of that force;
//   slip -> open     where dn rises through 0;
//   slip -> closed   where the slip rate s . d(a~)/dlambda turns negative, a~ = P du -
//                    s mu kn (-dn) / ks the anchor that keeps the force on the cone: on an
//                    affine path that rate is constant, so it turns only at a path's
//                    start (after another event changed the path); the anchor stays
//                    where the contact had slid to.
// At a fixed lambda (settling) the same rules with a tolerance: a closed contact whose
// force exceeds the cone by more than kn 1e-12 a slips; a slipping one whose anchor went
// back by more than 1e-12 a (kn / ks) since the last commit sticks. The small numbers
// are the frictionless contact's (contact_law.h). Friction is 2-D only in this version
// (docs/model.md, friction: why, and what 3-D needs).
#pragma once

#include "latfrac/mechanics/interaction_law.h"

namespace latfrac {

class FrictionalContactLaw final : public InteractionLaw {
 public:
  // spacing: the lattice spacing a, m; friction: mu, dimensionless (> 0).
  FrictionalContactLaw(double spacing, double friction)
      : friction_(friction), switch_tolerance_(1e-12 * spacing), rate_threshold_(1e-9 * spacing) {}

  Vec3 tension(const PairSprings& pair, PairState state, const Vec3& du) const override;
  Mat3 tangent(const PairSprings& pair, PairState state, const Vec3& du) const override;
  Mat3 jacobian(const PairSprings& pair, PairState state, const Vec3& du) const override;
  std::vector<RankOneTerm> stiffness_terms(const PairSprings& pair, PairState state) const override;
  std::vector<CouplingTerm> coupling_terms(const PairSprings& pair, PairState state) const override;
  bool is_linear() const override { return true; }

  PairState settled_state(const PairSprings& pair, PairState state, const Vec3& du) const override;
  PairSwitch next_switch(const PairSprings& pair, PairState state, const Vec3& du0,
                         const Vec3& du1, double from, double to, bool at_from) const override;

  bool remembers() const override { return true; }
  ContactMemory advanced(const PairSprings& pair, PairState state, const Vec3& du) const override;
  ContactMemory entered(const PairSprings& pair, PairState from, PairState to, const Vec3& du,
                        const Vec3& direction) const override;

  // The in-plane tangent of a pair (n0 turned by 90 degrees in the x-z plane).
  static Vec3 tangent_of(const Vec3& direction) { return {-direction.z(), 0, direction.x()}; }

 private:
  double friction_;
  double switch_tolerance_;  // m
  double rate_threshold_;    // m per unit lambda
};

}  // namespace latfrac
