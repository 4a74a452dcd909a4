// The frictional contact of a broken bond: stick, slip, and the events between them.
#include "latfrac/mechanics/friction_law.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "latfrac/base/error.h"

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

// A switch function g(s) = g0 + rate s on [from, to]: where it rises through 0 (or at
// `from`, for one already at or past 0 that moves on at more than `threshold`, when
// at_from allows), if before the first switch found so far.
void consider_switch(PairSwitch& first, double g0, double rate, double threshold, PairState into,
                     const Vec3& direction, double from, double to, bool at_from) {
  if (!(rate > 0)) return;
  const bool past = g0 + rate * from >= 0;
  if (past && (!at_from || rate <= threshold)) return;
  const double s = past ? from : -g0 / rate;
  if ((past || s > from) && s <= to && s < first.s) first = {s, into, direction};
}

}  // namespace

FrictionalContactLaw::FrictionalContactLaw(double spacing, double friction, int facets)
    : friction_(friction),
      facets_(facets),
      cos_half_(facets > 0 ? std::cos(std::numbers::pi / facets) : 1.0),
      switch_tolerance_(1e-12 * spacing),
      rate_threshold_(1e-9 * spacing) {
  if (facets != 0 && (facets < 3 || facets > max_facets))
    throw Error("friction_facets must be from 3 to " + std::to_string(max_facets));
  // Half steps pi h / k: corner i at h = 2i, facet i's normal at h = 2i + 1.
  for (int h = 0; h < 2 * facets; ++h) {
    const double angle = std::numbers::pi * h / facets;
    half_steps_.push_back({std::cos(angle), std::sin(angle)});
  }
}

// t1 lies in the horizontal plane unless n0 is near the vertical (then t1 is normal to
// n0 and x); t2 = n0 x t1.
std::pair<Vec3, Vec3> FrictionalContactLaw::frame_of(const Vec3& n) {
  const Vec3 reference = std::abs(n.z()) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
  const Vec3 t1 = reference.cross(n).normalized();
  return {t1, n.cross(t1)};
}

Vec3 FrictionalContactLaw::half_step(const Frame& frame, int h) const {
  const auto& [c, s] = half_steps_[static_cast<std::size_t>(((h % (2 * facets_)) + 2 * facets_) %
                                                            (2 * facets_))];
  return c * frame.first + s * frame.second;
}

int FrictionalContactLaw::pressed_facet(const Frame& frame, const Vec3& x) const {
  int best = 0;
  double most = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < facets_; ++j) {
    const double g = facet_normal(frame, j).dot(x);
    if (g > most) most = g, best = j;
  }
  return best;
}

int FrictionalContactLaw::index_of(const Frame& frame, const Vec3& s, bool edge) const {
  const auto& [t1, t2] = frame;
  const double turns = std::atan2(s.dot(t2), s.dot(t1)) / (2 * std::numbers::pi) * facets_;
  const long i = std::lround(edge ? turns : turns - 0.5);
  return static_cast<int>(((i % facets_) + facets_) % facets_);
}

Vec3 FrictionalContactLaw::sliding_force(const PairSprings& pair, PairState state,
                                         const Vec3& du) const {
  const Vec3& n = pair.direction;
  const ContactMemory& m = memory_of(pair);
  const Vec3 force = friction_ * pair.kn * -n.dot(du) * m.slip_direction;
  if (state != PairState::slip) return force;
  const Vec3 e = n.cross(m.slip_direction).normalized();
  return force + pair.ks * e.dot(du - m.anchor) * e;
}

std::pair<double, double> FrictionalContactLaw::on_edge_facets(const Frame& frame, int i,
                                                               const Vec3& x) const {
  const Vec3 mp = facet_normal(frame, i - 1), mq = facet_normal(frame, i);
  const double b = mp.dot(mq), xp = mp.dot(x), xq = mq.dot(x);
  const double det = 1 - b * b;
  return {(xp - b * xq) / det, (xq - b * xp) / det};
}

std::uint8_t FrictionalContactLaw::cycle_code(const PairSprings& pair, PairState state) const {
  if (state == PairState::closed) return 1;
  if (!slides(state)) return 0;
  const ContactMemory& m = memory_of(pair);
  if (facets_ == 0) return m.slip_direction.dot(tangent_of(pair.direction)) >= 0 ? 2 : 3;
  const int i = index_of(frame_of(pair.direction), m.slip_direction, state == PairState::slip_edge);
  return static_cast<std::uint8_t>(2 + i + (state == PairState::slip_edge ? facets_ : 0));
}

Vec3 FrictionalContactLaw::tension(const PairSprings& pair, PairState state, const Vec3& du) const {
  const double dn = pair.direction.dot(du);
  if (state == PairState::closed)
    return pair.kn * dn * pair.direction + pair.ks * (tangential(pair, du) - memory_of(pair).anchor);
  if (state == PairState::slip && facets_ == 0)
    return pair.kn * dn * pair.direction - friction_ * pair.kn * dn * memory_of(pair).slip_direction;
  if (slides(state)) return pair.kn * dn * pair.direction + sliding_force(pair, state, du);
  return Vec3::Zero();
}

Mat3 FrictionalContactLaw::tangent(const PairSprings& pair, PairState state, const Vec3&) const {
  const Mat3 normal = pair.direction * pair.direction.transpose();
  if (state == PairState::closed || slides(state))
    return pair.kn * normal + pair.ks * (Mat3::Identity() - normal);
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
  if (facets_ > 0 && (state == PairState::closed || slides(state))) {
    const auto [t1, t2] = frame_of(pair.direction);
    return {{pair.kn, pair.direction}, {pair.ks, t1}, {pair.ks, t2}};
  }
  // 2-D: a sliding contact keeps the stick spring too (coupling_terms takes it back).
  if (state == PairState::closed || state == PairState::slip)
    return {{pair.kn, pair.direction}, {pair.ks, tangent_of(pair.direction)}};
  return {};
}

std::vector<CouplingTerm> FrictionalContactLaw::coupling_terms(const PairSprings& pair,
                                                               PairState state) const {
  if (!slides(state)) return {};
  const Vec3& s = memory_of(pair).slip_direction;
  if (facets_ > 0 && state == PairState::slip) {
    // -m (ks m + c mu kn n0)': the facet's tangent less the stick stiffness the factor holds.
    const Vec3 m = s.normalized();
    const Vec3 r = pair.ks * m + cos_half_ * friction_ * pair.kn * pair.direction;
    return {{-r.norm(), m, r.normalized()}};
  }
  // -s (ks s + mu kn n0)': the slip's tangent less the stick spring the factor holds along
  // s (2-D: ks t t' = ks s s', s = +-t).
  const Vec3 r = pair.ks * s + friction_ * pair.kn * pair.direction;
  if (facets_ == 0) return {{-r.norm(), s, r.normalized()}};
  // 3-D's edge: s = w_i, the corner's unit direction; the factor also holds ks e e' across
  // it (e = n0 x w_i), which the second term takes back. Two columns of W.
  const Vec3 e = pair.direction.cross(s).normalized();
  return {{-r.norm(), s, r.normalized()}, {-pair.ks, e, e}};
}

PairTarget FrictionalContactLaw::settled_state(const PairSprings& pair, PairState state,
                                               const Vec3& du) const {
  if (facets_ > 0) return settled_3d(pair, state, du);
  const double dn = pair.direction.dot(du);
  const double force_tolerance = pair.kn * switch_tolerance_;
  const ContactMemory& m = memory_of(pair);
  switch (state) {
    case PairState::open:
      return {dn < -switch_tolerance_ ? PairState::closed : state};
    case PairState::closed: {
      if (dn > switch_tolerance_) return {PairState::open};
      const double trial = pair.ks * tangent_of(pair.direction).dot(du - m.anchor);
      return {std::abs(trial) - friction_ * pair.kn * -dn > force_tolerance ? PairState::slip : state};
    }
    case PairState::slip: {
      if (dn > switch_tolerance_) return {PairState::open};
      const double back = pair.ks * m.slip_direction.dot(du - m.anchor) + friction_ * pair.kn * dn;
      return {back < -force_tolerance ? PairState::closed : state};
    }
    default:
      return {state};
  }
}

// Each switch function g(s) = g0 + rate s is affine on the path; a switch is where one
// rises through 0. Like the frictionless contact (contact_law.h), a pair already at or past
// a switch and moving on switches at the path's start when at_from allows it and its rate
// is above the rounding threshold.
PairSwitch FrictionalContactLaw::next_switch(const PairSprings& pair, PairState state,
                                             const Vec3& du0, const Vec3& du1, double from,
                                             double to, bool at_from) const {
  if (facets_ > 0) return next_switch_3d(pair, state, du0, du1, from, to, at_from);
  PairSwitch first;
  auto consider = [&](double g0, double rate, double threshold, PairState into, const Vec3& d) {
    consider_switch(first, g0, rate, threshold, into, d, from, to, at_from);
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
  if (facets_ > 0) {
    if (slides(state) && pair.ks > 0) {
      const Vec3 anchor = tangential(pair, du) - sliding_force(pair, state, du) / pair.ks;
      const Vec3 moved = anchor - m.anchor;
      const double along = m.slip_direction.dot(moved);  // the work per unit mu kn (-dn)
      if (along > 0) {
        m.slip += moved.norm();
        m.work += friction_ * pair.kn * -(m.normal + dn) / 2 * along;
        m.anchor = anchor;
      }
    }
    m.normal = dn;
    return m;
  }
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
  if (facets_ > 0) return entered_3d(pair, from, to, du, direction);
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

// ---- 3-D: the polyhedral cone (friction_law.h) ----

PairTarget FrictionalContactLaw::settled_3d(const PairSprings& pair, PairState state,
                                            const Vec3& du) const {
  const Vec3& n = pair.direction;
  const double dn = n.dot(du);
  const double force_tolerance = pair.kn * switch_tolerance_;
  const double limit = cos_half_ * friction_ * pair.kn * -dn;  // c mu kn (-dn)
  const ContactMemory& m = memory_of(pair);
  if (state == PairState::open) return {dn < -switch_tolerance_ ? PairState::closed : state};
  if (!(state == PairState::closed || slides(state))) return {state};
  if (dn > switch_tolerance_) return {PairState::open};
  if (pair.ks <= 0) return {state};
  const Frame f = frame_of(n);
  if (state == PairState::closed) {
    const Vec3 mj = facet_normal(f, pressed_facet(f, du - m.anchor));
    if (pair.ks * mj.dot(du - m.anchor) - limit > force_tolerance)
      return {PairState::slip, cos_half_ * mj};
    return {state};
  }
  if (state == PairState::slip) {
    const int i = index_of(f, m.slip_direction, false);
    if (pair.ks * facet_normal(f, i).dot(du - m.anchor) - limit < -force_tolerance)
      return {PairState::closed};
    const Vec3 force = sliding_force(pair, state, du);
    const double g_next = facet_normal(f, i + 1).dot(force) - limit;
    const double g_previous = facet_normal(f, i - 1).dot(force) - limit;
    if (std::max(g_next, g_previous) > force_tolerance)
      return {PairState::slip_edge, corner(f, g_next >= g_previous ? i + 1 : i)};
    return {state};
  }
  // slip_edge at corner v: the slip since the last commit, on the corner's two facets.
  const int v = index_of(f, m.slip_direction, true);
  const Vec3 moved = tangential(pair, du) - sliding_force(pair, state, du) / pair.ks - m.anchor;
  const auto [gp, gq] = on_edge_facets(f, v, moved);
  const bool leaves_p = pair.ks * gp < -force_tolerance, leaves_q = pair.ks * gq < -force_tolerance;
  if (leaves_p && leaves_q) return {PairState::closed};
  if (leaves_p) return {PairState::slip, cos_half_ * facet_normal(f, v)};
  if (leaves_q) return {PairState::slip, cos_half_ * facet_normal(f, v - 1)};
  return {state};
}

PairSwitch FrictionalContactLaw::next_switch_3d(const PairSprings& pair, PairState state,
                                                const Vec3& du0, const Vec3& du1, double from,
                                                double to, bool at_from) const {
  PairSwitch first;
  auto consider = [&](double g0, double rate, double threshold, PairState into, const Vec3& d) {
    consider_switch(first, g0, rate, threshold, into, d, from, to, at_from);
  };
  auto at_start = [&](PairState into, const Vec3& d) {
    if (at_from && from < first.s) first = {from, into, d};
  };
  const Vec3& n = pair.direction;
  const double dn0 = n.dot(du0), dn1 = n.dot(du1);
  const ContactMemory& m = memory_of(pair);
  const double force_threshold = pair.kn * rate_threshold_;
  const double friction_kn = cos_half_ * friction_ * pair.kn;  // c mu kn
  if (state == PairState::open) {
    consider(-dn0, -dn1, rate_threshold_, PairState::closed, Vec3::Zero());
    return first;
  }
  if (!(state == PairState::closed || slides(state))) return first;
  consider(dn0, dn1, rate_threshold_, PairState::open, Vec3::Zero());
  if (pair.ks <= 0) return first;
  const Frame f = frame_of(n);
  if (state == PairState::closed) {
    auto g = [&](int j, double s) {  // facet j's switch function at s
      const Vec3 mj = facet_normal(f, j);
      return pair.ks * mj.dot(du0 + s * du1 - m.anchor) + friction_kn * (dn0 + s * dn1);
    };
    for (int j = 0; j < facets_; ++j) {
      const Vec3 mj = facet_normal(f, j);
      consider(pair.ks * mj.dot(du0 - m.anchor) + friction_kn * dn0,
               pair.ks * mj.dot(du1) + friction_kn * dn1, force_threshold, PairState::slip,
               cos_half_ * mj);
    }
    // The force leaves the cone at a corner (both facets there reach their limit together,
    // as where a contact that stuck on an edge slips again): the first crossing is then
    // rounding's choice. The force's rate decides instead, as a projection onto the cone
    // would: on the corner's two facets, r = g_p m_p + g_q m_q with r the rate of the
    // force relative to the corner; both parts positive slide on the edge, else the
    // contact slides along the facet whose part is positive.
    if (first.found() && first.to == PairState::slip) {
      const int j = index_of(f, first.direction, false);
      for (const int v : {j, j + 1}) {
        const int other = v == j ? j - 1 : j + 1;
        if (g(other, first.s) < -pair.kn * switch_tolerance_) continue;
        const Vec3 rate =
            tangential(pair, du1) + (friction_ * pair.kn * dn1 / pair.ks) * corner(f, v);
        const auto [gp, gq] = on_edge_facets(f, v, rate);
        if (gp > 0 && gq > 0) {
          first.to = PairState::slip_edge;
          first.direction = corner(f, v);
        } else {
          first.direction = cos_half_ * facet_normal(f, gp > 0 ? v - 1 : v);
        }
        break;
      }
    }
  } else if (state == PairState::slip) {
    const int i = index_of(f, m.slip_direction, false);
    const Vec3 mi = facet_normal(f, i);
    if (pair.ks * mi.dot(du1) + friction_kn * dn1 < -force_threshold)
      at_start(PairState::closed, Vec3::Zero());
    // Sliding along the facet, the force meets an adjacent facet's limit at a corner.
    const Vec3 e = n.cross(mi).normalized();
    for (const int j : {i - 1, i + 1}) {
      const Vec3 mj = facet_normal(f, j);
      const double gap = mj.dot(mi) - 1;  // (m_j . m_i - 1) < 0
      const double along = mj.dot(e);
      consider(-friction_kn * dn0 * gap + pair.ks * along * e.dot(du0 - m.anchor),
               -friction_kn * dn1 * gap + pair.ks * along * e.dot(du1), force_threshold,
               PairState::slip_edge, corner(f, j > i ? i + 1 : i));
    }
  } else {
    const int v = index_of(f, m.slip_direction, true);
    const Vec3 rate = tangential(pair, du1) + (friction_ * pair.kn * dn1 / pair.ks) * m.slip_direction;
    const auto [gp, gq] = on_edge_facets(f, v, rate);
    const bool leaves_p = pair.ks * gp < -force_threshold;
    const bool leaves_q = pair.ks * gq < -force_threshold;
    if (leaves_p && leaves_q) at_start(PairState::closed, Vec3::Zero());
    else if (leaves_p) at_start(PairState::slip, cos_half_ * facet_normal(f, v));
    else if (leaves_q) at_start(PairState::slip, cos_half_ * facet_normal(f, v - 1));
  }
  return first;
}

ContactMemory FrictionalContactLaw::entered_3d(const PairSprings& pair, PairState from,
                                               PairState to, const Vec3& du,
                                               const Vec3& direction) const {
  ContactMemory m = memory_of(pair);
  const Vec3& n = pair.direction;
  const double dn = n.dot(du);
  m.normal = dn;
  // A contact that was not touching starts sticking unstretched (as in 2-D).
  if (!(from == PairState::closed || slides(from))) m.anchor = tangential(pair, du);
  if (to == PairState::closed) {
    m.slip_direction = Vec3::Zero();
  } else if (to == PairState::slip || to == PairState::slip_edge) {
    const Frame f = frame_of(n);
    if (direction.squaredNorm() > 0) {
      m.slip_direction = direction;
    } else if (to == PairState::slip) {  // the facet the stick force presses hardest
      m.slip_direction = cos_half_ * facet_normal(f, pressed_facet(f, du - m.anchor));
    } else {
      // From facet i: the corner towards which the force slides.
      const int i = index_of(f, m.slip_direction, false);
      const Vec3 e = n.cross(facet_normal(f, i)).normalized();
      const bool next = facet_normal(f, i + 1).dot(e) * e.dot(du - m.anchor) >= 0;
      m.slip_direction = corner(f, next ? i + 1 : i);
    }
  }
  return m;
}

}  // namespace latfrac
