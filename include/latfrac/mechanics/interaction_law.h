// The interaction laws: a pair's force, its tangent and its switch functions, by state.
//
// Every pair interaction goes through one law object: the intact bond's springs (a
// BondLaw, bond_law.h) and the contact that a broken bond leaves (contact_law.h). A law
// gives, for the pair's state:
//   - its tension t (the force on node j; node i feels -t) at the relative displacement
//     du = u_j - u_i, and its tangent dt/d(du), whose symmetric part the stiffness holds;
//   - its stiffness as weighted rank-1 terms sum w d d' (for a linear law, the exact
//     tangent): what a factor update removes when the pair leaves the state and adds when
//     it enters it;
//   - its switch functions: the state the pair should be in at du (settling at a fixed
//     lambda) and the first point of an affine path du(s) = du0 + s du1 where that state
//     changes (an event). A law whose pairs never switch has none.
// A new kind of interaction (frictional contact, say) is a new law class and the states it
// adds; the assembly, the solvers and the event loop ask the law and need no edit.
#pragma once

#include <limits>
#include <vector>

#include "latfrac/base/linear_algebra.h"
#include "latfrac/mechanics/pair_state.h"

namespace latfrac {

// What a frictional contact remembers between events (friction_law.h). Relative
// displacements are du = u_j - u_i, m.
struct ContactMemory {
  // Stick: the tangential relative displacement at which the tangential spring is
  // unstretched. Slip: that of the last commit (where the contact had slid to).
  Vec3 anchor = Vec3::Zero();
  Vec3 slip_direction = Vec3::Zero();  // slip: the unit sense in which node j slides
  double normal = 0;  // dn = n0 . du at the last commit, m
  double slip = 0;    // slip accumulated over the run, m
  double work = 0;    // work dissipated by friction, J (2-D: J per metre)
};

// A pair's reference geometry and springs: unit vector n0 from node i to node j, length
// L0 (m), normal and shear stiffness (N/m, or N/m per metre in 2-D), and, for a law that
// remembers (frictional contact), the pair's memory.
struct PairSprings {
  const Vec3& direction;
  double length;
  double kn;
  double ks;
  const ContactMemory* memory = nullptr;
};

// One rank-1 stiffness term w d d' (w in N/m, d a unit vector).
struct RankOneTerm {
  double weight;
  Vec3 direction;
};

// One nonsymmetric rank-1 part of a tangent, w a b' (w in N/m, a and b unit vectors):
// what the factor of the symmetric stiffness does not hold (a slipping contact).
struct CouplingTerm {
  double weight;
  Vec3 left, right;
};

// The state a pair should be in (settling), and for a frictional contact entering slip the
// sense of sliding (zero: the law picks it from the force, entered()).
struct PairTarget {
  PairState state;
  Vec3 direction = Vec3::Zero();
};

// Where a pair switches on an affine path: at s, into `to` (into slip: along `direction`).
struct PairSwitch {
  double s = std::numeric_limits<double>::infinity();  // +inf: no switch before the end
  PairState to = PairState::open;
  Vec3 direction = Vec3::Zero();
  bool found() const { return s < std::numeric_limits<double>::infinity(); }
};

class InteractionLaw {
 public:
  virtual ~InteractionLaw() = default;
  virtual Vec3 tension(const PairSprings& pair, PairState state, const Vec3& du) const = 0;
  // The symmetric stiffness block the assembly factorizes: dt/d(du) when that is
  // symmetric; otherwise a symmetric block that coupling_terms() corrects to dt/d(du)
  // (a sliding contact keeps its stick stiffness here).
  virtual Mat3 tangent(const PairSprings& pair, PairState state, const Vec3& du) const = 0;
  // dt/d(du) exactly (nonsymmetric for large kinematics).
  virtual Mat3 jacobian(const PairSprings& pair, PairState state, const Vec3& du) const {
    return tangent(pair, state, du);
  }
  // The stiffness of the state at rest as rank-1 terms (empty: none).
  virtual std::vector<RankOneTerm> stiffness_terms(const PairSprings& pair,
                                                   PairState state) const = 0;
  // True when the tension is linear in du (equilibrium paths are affine).
  virtual bool is_linear() const = 0;
  // The part of dt/d(du) that stiffness_terms() leaves out (nonsymmetric): the solver
  // adds it to the factor's answer (solvers/equilibrium.h). Empty for most laws.
  virtual std::vector<CouplingTerm> coupling_terms(const PairSprings&, PairState) const {
    return {};
  }

  // Laws whose pairs remember their history (a frictional contact's anchor, its slip and
  // dissipated work; ContactMemory). advanced(): the memory carried along to du (the
  // slip since the last commit added, its work by the trapezoidal rule in dn, exact on
  // an affine path; a slip that went back is not taken: the settling makes that contact
  // stick where it was); entered(): the memory on entering `to` from `from` at du (into
  // slip along `direction`, or the sense of the tangential force when it is zero).
  virtual bool remembers() const { return false; }
  virtual ContactMemory advanced(const PairSprings& pair, PairState, const Vec3&) const {
    return pair.memory ? *pair.memory : ContactMemory{};
  }
  virtual ContactMemory entered(const PairSprings& pair, PairState /*from*/, PairState /*to*/,
                                const Vec3& /*du*/, const Vec3& /*direction*/) const {
    return pair.memory ? *pair.memory : ContactMemory{};
  }

  // The state the pair should be in at du: its own when the state is consistent.
  virtual PairTarget settled_state(const PairSprings&, PairState state, const Vec3&) const {
    return {state};
  }
  // Whether the pair's force in `state` has a constant part (a stick anchor): the solver
  // takes it as a load (solvers/equilibrium.h).
  virtual bool anchored(PairState) const { return false; }
  // A small code for the pair's state, telling apart what the settling's cycle rule must
  // (pair_settling.h): 0 open or intact, 1 closed, 2 and up a sense or facet of slip.
  virtual std::uint8_t cycle_code(const PairSprings&, PairState state) const {
    return state == PairState::closed ? 1 : 0;
  }
  // On du(s) = du0 + s du1: the first s in (from, to] where the state changes; `at_from`
  // also allows s = from, for a pair already at or past its switch and moving on (a tie
  // with a switch just made, or rounding). None when the pairs of this law never switch.
  virtual PairSwitch next_switch(const PairSprings&, PairState, const Vec3& /*du0*/,
                                 const Vec3& /*du1*/, double /*from*/, double /*to*/,
                                 bool /*at_from*/) const {
    return {};
  }
};

}  // namespace latfrac
