// The frictional contact of a broken bond: stick, slip, and the events between them.
#include "latfrac/mechanics/friction_law.h"

#include <cmath>

namespace latfrac {

namespace {

const ContactMemory& memory_of(const PairSprings& pair) {
  static const ContactMemory none;
  return pair.memory ? *pair.memory : none;
}

// The tangential part P du = du - (n0 . du) n0.
Vec3 tangential(const PairSprings& pair, const Vec3& du) {
  return du - pair.direction.dot(du) * pair.direction;
}

}  // namespace

Vec3 FrictionalContactLaw::tension(const PairSprings& pair, PairState state, const Vec3& du) const {
  const double dn = pair.direction.dot(du);
  if (state == PairState::closed)
    return pair.kn * dn * pair.direction + pair.ks * (tangential(pair, du) - memory_of(pair).anchor);
  if (state == PairState::slip)
    return pair.kn * dn * pair.direction - friction_ * pair.kn * dn * memory_of(pair).slip_direction;
  return Vec3::Zero();
}

Mat3 FrictionalContactLaw::tangent(const PairSprings& pair, PairState state, const Vec3&) const {
  const Mat3 normal = pair.direction * pair.direction.transpose();
  if (state == PairState::closed) return pair.kn * normal + pair.ks * (Mat3::Identity() - normal);
  if (state == PairState::slip) return pair.kn * normal;
  return Mat3::Zero();
}

Mat3 FrictionalContactLaw::jacobian(const PairSprings& pair, PairState state,
                                    const Vec3& du) const {
  Mat3 j = tangent(pair, state, du);
  for (const CouplingTerm& c : coupling_terms(pair, state))
    j += c.weight * c.left * c.right.transpose();
  return j;
}

std::vector<RankOneTerm> FrictionalContactLaw::stiffness_terms(const PairSprings& pair,
                                                               PairState state) const {
  if (state == PairState::closed)
    return {{pair.kn, pair.direction}, {pair.ks, tangent_of(pair.direction)}};
  if (state == PairState::slip) return {{pair.kn, pair.direction}};
  return {};
}

std::vector<CouplingTerm> FrictionalContactLaw::coupling_terms(const PairSprings& pair,
                                                               PairState state) const {
  if (state != PairState::slip) return {};
  return {{-friction_ * pair.kn, memory_of(pair).slip_direction, pair.direction}};
}

PairState FrictionalContactLaw::settled_state(const PairSprings& pair, PairState state,
                                              const Vec3& du) const {
  const double dn = pair.direction.dot(du);
  const double force_tolerance = pair.kn * switch_tolerance_;
  const ContactMemory& m = memory_of(pair);
  switch (state) {
    case PairState::open:
      return dn < -switch_tolerance_ ? PairState::closed : state;
    case PairState::closed: {
      if (dn > switch_tolerance_) return PairState::open;
      const double trial = pair.ks * tangent_of(pair.direction).dot(du - m.anchor);
      return std::abs(trial) - friction_ * pair.kn * -dn > force_tolerance ? PairState::slip : state;
    }
    case PairState::slip: {
      if (dn > switch_tolerance_) return PairState::open;
      const double back = pair.ks * m.slip_direction.dot(du - m.anchor) + friction_ * pair.kn * dn;
      return back < -force_tolerance ? PairState::closed : state;
    }
    default:
      return state;
  }
}

// Each switch function g(s) = g0 + rate s is affine on the path; a switch is where one
// rises through 0. Like the frictionless contact (contact_law.h), a pair already at or past
// a switch and moving on switches at the path's start when at_from allows it and its rate
// is above the rounding threshold.
PairSwitch FrictionalContactLaw::next_switch(const PairSprings& pair, PairState state,
                                             const Vec3& du0, const Vec3& du1, double from,
                                             double to, bool at_from) const {
  PairSwitch first;
  auto consider = [&](double g0, double rate, double threshold, PairState into, const Vec3& d) {
    if (!(rate > 0)) return;
    const bool past = g0 + rate * from >= 0;
    if (past && (!at_from || rate <= threshold)) return;
    const double s = past ? from : -g0 / rate;
    if ((past || s > from) && s <= to && s < first.s) first = {s, into, d};
  };
  const Vec3& n = pair.direction;
  const double dn0 = n.dot(du0), dn1 = n.dot(du1);
  const ContactMemory& m = memory_of(pair);
  const double force_threshold = pair.kn * rate_threshold_;
  switch (state) {
    case PairState::open:
      consider(-dn0, -dn1, rate_threshold_, PairState::closed, Vec3::Zero());
      break;
    case PairState::closed: {
      consider(dn0, dn1, rate_threshold_, PairState::open, Vec3::Zero());
      const Vec3 t = tangent_of(n);
      for (const double sense : {1.0, -1.0}) {
        const double g0 = sense * pair.ks * t.dot(du0 - m.anchor) + friction_ * pair.kn * dn0;
        const double rate = sense * pair.ks * t.dot(du1) + friction_ * pair.kn * dn1;
        consider(g0, rate, force_threshold, PairState::slip, Vec3(sense * t));
      }
      break;
    }
    case PairState::slip: {
      consider(dn0, dn1, rate_threshold_, PairState::open, Vec3::Zero());
      const double rate = pair.ks * m.slip_direction.dot(du1) + friction_ * pair.kn * dn1;
      if (at_from && rate < -force_threshold && from < first.s)
        first = {from, PairState::closed, Vec3::Zero()};
      break;
    }
    default:
      break;
  }
  return first;
}

ContactMemory FrictionalContactLaw::advanced(const PairSprings& pair, PairState state,
                                             const Vec3& du) const {
  ContactMemory m = memory_of(pair);
  const double dn = pair.direction.dot(du);
  if (state == PairState::slip && pair.ks > 0) {
    const Vec3 anchor =
        tangential(pair, du) - (friction_ * pair.kn * -dn / pair.ks) * m.slip_direction;
    // Slip runs one way: an anchor that went back (a jump at fixed lambda, or a contact
    // left slipping against its rate) stays, and settling makes the contact stick there.
    const double slid = m.slip_direction.dot(anchor - m.anchor);
    if (slid > 0) {
      m.slip += slid;
      m.work += friction_ * pair.kn * -(m.normal + dn) / 2 * slid;
      m.anchor = anchor;
    }
  }
  m.normal = dn;
  return m;
}

ContactMemory FrictionalContactLaw::entered(const PairSprings& pair, PairState from, PairState to,
                                            const Vec3& du, const Vec3& direction) const {
  ContactMemory m = memory_of(pair);
  m.normal = pair.direction.dot(du);
  if (to == PairState::closed) {
    // From slip the contact sticks where it had slid to (the memory advanced to du).
    if (from != PairState::slip) m.anchor = tangential(pair, du);
    m.slip_direction = Vec3::Zero();
  } else if (to == PairState::slip) {
    const Vec3 t = tangent_of(pair.direction);
    m.slip_direction = direction.squaredNorm() > 0 ? direction
                       : t.dot(du - m.anchor) < 0  ? Vec3(-t)
                                                   : t;
  }
  return m;
}

}  // namespace latfrac
