// The contact a broken bond leaves, with Coulomb friction: a compression-only normal
// spring kn, and a tangential spring ks that sticks until its force reaches mu |Fn|, then
// slides.
//
// 2-D. States (pair_state.h), with dn = n0 . du, the tangent t = n0 turned by 90 degrees in the
// lattice's plane, and the pair's memory (ContactMemory: anchor a, sense of slip s):
//   open:   nothing acts.
//   closed: sticks: t_force = kn dn n0 + ks (P du - a), P = I - n0 n0' (a linear law with
//           a constant term -ks a: the anchored spring is a load).
//   slip:   slides along s: t_force = kn dn n0 + mu kn (-dn) s. Its tangent
//           kn n0 n0' - mu kn s n0' is nonsymmetric; the factor holds the stick stiffness
//           kn n0 n0' + ks t t' (so stick and slip share it) and the solver adds the rest,
//           -s (ks s + mu kn n0)' (coupling_terms; solvers/equilibrium.h).
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
// are the frictionless contact's (contact_law.h).
//
// In 3-D the tangential plane has two directions and Coulomb's circular cone would turn
// the slip direction along the path. The law replaces the circle by a regular polygon of
// k facets inscribed in it (its corners on the circle; k = [contact] friction_facets),
// which keeps every path affine (docs/model.md, friction in 3-D). With an orthonormal
// frame (t1, t2) of the tangential plane fixed by n0 (frame_of), corner i is
// w_i = cos(2 pi i/k) t1 + sin(2 pi i/k) t2, facet i lies between corners i and i + 1
// with outward normal m_i (at angle 2 pi (i + 1/2)/k) and its limit is
// m_i . Ft <= c mu kn (-dn), c = cos(pi/k). The memory's slip_direction s is the
// tangential force per unit mu kn (-dn): c m_i on facet i, w_i on edge i.
//   closed:    sticks: t_force = kn dn n0 + ks (P du - a).
//   slip:      on facet i: t_force = kn dn n0 + mu kn (-dn) s + ks e e' (du - a), e the
//              facet's direction (n0 x m_i): along the facet the contact still sticks.
//              The factor holds the stick stiffness kn n0 n0' + ks P; the rest,
//              -m_i (ks m_i + c mu kn n0)', is one coupling term.
//   slip_edge: on edge i: t_force = kn dn n0 + mu kn (-dn) w_i (factor: kn n0 n0').
// Switches (all affine in lambda):
//   closed -> slip (facet j)    where ks m_j . (du - a) + c mu kn dn rises through 0;
//                               at a corner (both facets there reach their limits
//                               together) the force's rate relative to the corner,
//                               on the two facets' normals, decides as a projection
//                               would: the edge if both parts are positive, else the
//                               facet whose part is positive;
//   slip -> slip_edge           where the force, sliding along facet i, reaches an
//                               adjacent facet's limit;
//   slip -> closed              where the slip rate ks m_i . du' + c mu kn dn' < 0
//                               (only at a path's start, as in 2-D);
//   slip_edge -> slip or closed where the slip rate P du' + mu kn dn' w_i / ks, written
//                               as g_p m_p + g_q m_q on the edge's two facets, has a
//                               negative part (at a path's start): the contact leaves the
//                               facet whose part is negative, or sticks if both are;
//   any -> open                 where dn rises through 0.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "latfrac/mechanics/interaction_law.h"

namespace latfrac {

class FrictionalContactLaw final : public InteractionLaw {
 public:
  // spacing: the lattice spacing a, m; friction: mu, dimensionless (> 0); facets: 0 for a
  // 2-D lattice, k >= 3 (the polygon's facets) for a 3-D one.
  FrictionalContactLaw(double spacing, double friction, int facets = 0);

  Vec3 tension(const PairSprings& pair, PairState state, const Vec3& du) const override;
  Mat3 tangent(const PairSprings& pair, PairState state, const Vec3& du) const override;
  Mat3 jacobian(const PairSprings& pair, PairState state, const Vec3& du) const override;
  std::vector<RankOneTerm> stiffness_terms(const PairSprings& pair, PairState state) const override;
  std::vector<CouplingTerm> coupling_terms(const PairSprings& pair, PairState state) const override;
  bool is_linear() const override { return true; }

  PairTarget settled_state(const PairSprings& pair, PairState state, const Vec3& du) const override;
  bool anchored(PairState state) const override {
    return state == PairState::closed || (facets_ > 0 && state == PairState::slip);
  }
  std::uint8_t cycle_code(const PairSprings& pair, PairState state) const override;
  PairSwitch next_switch(const PairSprings& pair, PairState state, const Vec3& du0,
                         const Vec3& du1, double from, double to, bool at_from) const override;

  bool remembers() const override { return true; }
  ContactMemory advanced(const PairSprings& pair, PairState state, const Vec3& du) const override;
  ContactMemory entered(const PairSprings& pair, PairState from, PairState to, const Vec3& du,
                        const Vec3& direction) const override;

  // The in-plane tangent of a pair (n0 turned by 90 degrees in the x-z plane).
  static Vec3 tangent_of(const Vec3& direction) { return {-direction.z(), 0, direction.x()}; }
  // 3-D: the tangential frame (t1, t2) of a pair, with t1 x t2 = n0.
  static std::pair<Vec3, Vec3> frame_of(const Vec3& direction);
  int facets() const { return facets_; }
  static constexpr int max_facets = 64;

 private:
  using Frame = std::pair<Vec3, Vec3>;  // (t1, t2), frame_of
  // 3-D: the unit vector at angle pi h / k in the frame (h taken modulo 2k); corner i and
  // facet i's outward normal.
  Vec3 half_step(const Frame& frame, int h) const;
  Vec3 corner(const Frame& frame, int i) const { return half_step(frame, 2 * i); }
  Vec3 facet_normal(const Frame& frame, int i) const { return half_step(frame, 2 * i + 1); }
  // 3-D: the facet whose normal has the largest projection of the tangential vector x.
  int pressed_facet(const Frame& frame, const Vec3& x) const;
  // 3-D: the facet (slip) or corner (slip_edge) that a slip direction s names.
  int index_of(const Frame& frame, const Vec3& s, bool edge) const;
  // 3-D: the tangential force in a sliding state.
  Vec3 sliding_force(const PairSprings& pair, PairState state, const Vec3& du) const;
  // 3-D: parts (g_p, g_q) of a tangential vector x on facets p = i - 1 and q = i, the two
  // facets that meet at corner i.
  std::pair<double, double> on_edge_facets(const Frame& frame, int i, const Vec3& x) const;
  PairTarget settled_3d(const PairSprings& pair, PairState state, const Vec3& du) const;
  ContactMemory entered_3d(const PairSprings& pair, PairState from, PairState to, const Vec3& du,
                           const Vec3& direction) const;
  PairSwitch next_switch_3d(const PairSprings& pair, PairState state, const Vec3& du0,
                            const Vec3& du1, double from, double to, bool at_from) const;

  double friction_;
  int facets_;
  double cos_half_;    // c = cos(pi / k)
  std::vector<std::pair<double, double>> half_steps_;  // cos and sin of pi h / k, h < 2k
  double switch_tolerance_;  // m
  double rate_threshold_;    // m per unit lambda
};

}  // namespace latfrac
