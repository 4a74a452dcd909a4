// Contact switches as events: the first pair whose law switches its state on the current
// affine path (a contact opening or closing, contact_law.h).
//
// At a switch the pair changes state, the contacts are settled and the cascade runs. Two
// switches at one lambda (ties, or a contact already at dn = 0) are taken one after the
// other. Should they bring back a set of closed contacts already met at that lambda, they
// cycle: this source then stops proposing switches at the lambda it stands at (the rest
// are left to the settling and its own cycle rule, pair_settling.h) until the loop moves
// on, and the cycle is counted (docs/robustness.md).
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "latfrac/fracture/breaking.h"
#include "latfrac/fracture/event_source.h"
#include "latfrac/fracture/run_control.h"

namespace latfrac {

class PairSwitchSource final : public EventSource {
 public:
  PairSwitchSource(EquilibriumState& equilibrium, PairSettling& settling, Breaking& breaking)
      : equilibrium_(equilibrium), settling_(settling), breaking_(breaking) {}
  double propose(const AffinePath& path, double from, double to) override;
  void reached(double lambda) override;
  void take(double lambda) override;
  // The guard against cycling, for a checkpoint and a resume.
  SwitchGuard guard() const;
  void restore(const SwitchGuard& guard);

 private:
  EquilibriumState& equilibrium_;
  PairSettling& settling_;
  Breaking& breaking_;
  PairChange proposed_{-1, PairState::open};
  // The sets of closed contacts met at the current lambda, and whether switches at the
  // path's start are still proposed there.
  std::set<std::string> sets_at_lambda_;
  double sets_lambda_ = EventSource::none;
  bool switch_at_start_ = true;
};

}  // namespace latfrac
