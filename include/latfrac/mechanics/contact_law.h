// The contact a broken bond leaves: a compression-only, frictionless normal spring kn.
//
// A contact is closed (its faces touch: the spring kn n0 n0' acts, a linear law) or open
// (nothing acts). Its switch function is the normal displacement dn = n0 . du: a closed
// contact opens where dn rises through 0, an open one closes where dn falls through 0
// (docs/model.md, contact). Two small numbers keep rounding from deciding a switch:
//   - settling at a fixed lambda switches only past a tolerance, 1e-12 a (a the lattice
//     spacing), so a contact that sits exactly at dn = 0 is not toggled by roundoff;
//   - on a path, a contact already at or past 0 and still moving the wrong way switches at
//     the path's start; a contact whose rate is below 1e-9 a per unit lambda, which
//     rounding could have given either sign, does not switch on the path at all (it moves
//     less than 1e-12 a per 1e-3 of lambda, 4e-11 a over the paper's whole loading to
//     0.04; where it would cross 0 is rounding's choice).
#pragma once

#include "latfrac/mechanics/interaction_law.h"

namespace latfrac {

class ContactLaw final : public InteractionLaw {
 public:
  // spacing: the lattice spacing a, m (the scale of the two tolerances above).
  explicit ContactLaw(double spacing)
      : switch_tolerance_(1e-12 * spacing), rate_threshold_(1e-9 * spacing) {}

  Vec3 tension(const PairSprings& pair, PairState state, const Vec3& du) const override;
  Mat3 tangent(const PairSprings& pair, PairState state, const Vec3& du) const override;
  std::vector<RankOneTerm> stiffness_terms(const PairSprings& pair, PairState state) const override;
  bool is_linear() const override { return true; }

  PairTarget settled_state(const PairSprings& pair, PairState state, const Vec3& du) const override;
  PairSwitch next_switch(const PairSprings& pair, PairState state, const Vec3& du0,
                         const Vec3& du1, double from, double to, bool at_from) const override;

 private:
  double switch_tolerance_;  // m
  double rate_threshold_;    // m per unit lambda
};

}  // namespace latfrac
