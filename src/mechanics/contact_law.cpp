// The frictionless contact of a broken bond: its spring, and where it opens and closes.
#include "latfrac/mechanics/contact_law.h"

#include <cmath>

namespace latfrac {

Vec3 ContactLaw::tension(const PairSprings& pair, PairState state, const Vec3& du) const {
  if (state != PairState::closed) return Vec3::Zero();
  return pair.kn * pair.direction.dot(du) * pair.direction;
}

Mat3 ContactLaw::tangent(const PairSprings& pair, PairState state, const Vec3&) const {
  if (state != PairState::closed) return Mat3::Zero();
  return pair.kn * pair.direction * pair.direction.transpose();
}

std::vector<RankOneTerm> ContactLaw::stiffness_terms(const PairSprings& pair,
                                                     PairState state) const {
  if (state != PairState::closed) return {};
  return {{pair.kn, pair.direction}};
}

PairTarget ContactLaw::settled_state(const PairSprings& pair, PairState state,
                                     const Vec3& du) const {
  const double dn = pair.direction.dot(du);
  if (state == PairState::closed && dn > switch_tolerance_) return {PairState::open};
  if (state == PairState::open && dn < -switch_tolerance_) return {PairState::closed};
  return {state};
}

// dn(s) = dn0 + rate s: a closed contact opens when it rises through 0, an open one
// closes when it falls through 0. A rate below rate_threshold_ is rounding's, of either
// sign, and so would be where it crosses 0: such a contact does not switch on the path
// (docs/robustness.md, "Continuity"; the settling still switches it once dn passes
// switch_tolerance_).
PairSwitch ContactLaw::next_switch(const PairSprings& pair, PairState state, const Vec3& du0,
                                   const Vec3& du1, double from, double to, bool at_from) const {
  const double dn0 = pair.direction.dot(du0);
  const double rate = pair.direction.dot(du1);
  const bool closed = state == PairState::closed;
  if (std::abs(rate) <= rate_threshold_ || (closed && rate < 0) || (!closed && rate > 0))
    return {};
  const bool past = closed ? dn0 + rate * from >= 0 : dn0 + rate * from <= 0;
  if (past && !at_from) return {};
  const double s = past ? from : -dn0 / rate;
  if ((past || s > from) && s <= to) return {s, closed ? PairState::open : PairState::closed};
  return {};
}

}  // namespace latfrac
