// Settling the pairs at a fixed lambda: every switching pair (a contact) in the state its
// law asks for at the current equilibrium.
//
// An active-set iteration: switch every pair whose law's settled_state() differs from its
// state (a contact that pulls opens, one that penetrates closes), re-equilibrate, repeat.
// The iteration ends when no pair wants to switch. If a set of closed contacts recurs, it
// is cycling (chattering): then only the switches that close are made, one more
// equilibrium is computed and the iteration stops; the few contacts left slightly
// pulling are checked again at the next event or step (docs/robustness.md). Every call
// ends: a repeated set always triggers that rule.
//
// Friction: a contact held slipping (unstable, pair_switch_source.h) is not made to stick
// here while it is held; every contact that settling makes stick from a slide is noted
// (taken_sticks) for the unstable-contact rule.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "latfrac/fracture/equilibrium_state.h"

namespace latfrac {

// Which pairs are closed contacts (one byte per bond: 1 if closed, 2 or 3 if slipping
// along the tangent or against it, 0 else): the set the cycle rule compares.
std::string closed_pairs(const Model& model);

class PairSettling {
 public:
  explicit PairSettling(EquilibriumState& equilibrium) : equilibrium_(equilibrium) {}
  // Settles at lambda; nothing to do in a model without contact.
  void settle(double lambda);
  // Iterations that cycled and were ended by the rule above (with the event loop's own
  // guard, contact_cycles in /summary).
  std::int64_t cycles() const { return cycles_; }
  void count_cycle() { ++cycles_; }
  // Friction: the contacts held slipping (the unstable-contact rule of
  // pair_switch_source.h, whose only record they are): settling does not make them stick.
  void hold(std::int64_t bond) { held_.insert(bond); }
  void release() { held_.clear(); }
  const std::set<std::int64_t>& held() const { return held_; }
  // The contacts settling made stick from a slide since the last call, with the lambda.
  std::vector<std::pair<std::int64_t, double>> taken_sticks() { return std::exchange(sticks_, {}); }

 private:
  EquilibriumState& equilibrium_;
  std::int64_t cycles_ = 0;
  std::set<std::int64_t> held_;
  std::vector<std::pair<std::int64_t, double>> sticks_;
};

}  // namespace latfrac
