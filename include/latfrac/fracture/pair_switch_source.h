// Contact switches as events: the first pair whose law switches its state on the current
// affine path (a contact opening or closing, contact_law.h).
//
// At a switch the pair changes state and the contacts are settled; a bond this brings to
// f >= 1 breaks as the next event, at the same lambda (event_loop.h). Two
// switches at one lambda (ties, or a contact already at dn = 0) are taken one after the
// other. Should they bring back a set of closed contacts already met at that lambda, they
// cycle: this source then stops proposing switches at the lambda it stands at (the rest
// are left to the settling and its own cycle rule, pair_settling.h) until the loop moves
// on, and the cycle is counted (docs/robustness.md).
//
// With friction a contact can have no consistent state on a path: sticking, its force
// leaves the cone at once; slipping, its slip runs backwards. It would then stick and slip
// again ever closer together (a Zeno sequence: measured, steps of 2e-13 in lambda). A
// contact that slips again within unstable_window of lambda after it stuck (at a switch
// taken here, or in a settling) is taken as unstable: it goes on slipping (its
// slip->stick switch is not proposed, and settling holds it, pair_settling.h) until the
// loop has moved on by more than the window, and the cycle is counted. Without the
// settling's part, a contact that the settling after its own slip made stick again (its
// anchor jumped back at fixed lambda) slipped again a few ulps later, for ever (measured:
// steps of 7e-16 in lambda, docs/robustness.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "latfrac/fracture/breaking.h"
#include "latfrac/fracture/event_source.h"
#include "latfrac/fracture/run_control.h"

namespace latfrac {

class PairSwitchSource final : public EventSource {
 public:
  PairSwitchSource(EquilibriumState& equilibrium, PairSettling& settling)
      : equilibrium_(equilibrium), settling_(settling) {}
  double propose(const AffinePath& path, double from, double to, double needed_until) override;
  void reached(double lambda) override;
  void take(double lambda) override;
  // The window: this times max(|lambda|, 1e-6).
  static constexpr double unstable_window = 1e-9;
  // The guard against cycling, for a checkpoint and a resume.
  SwitchGuard guard() const;
  void restore(const SwitchGuard& guard);

 private:
  EquilibriumState& equilibrium_;
  PairSettling& settling_;
  PairChange proposed_{-1, PairState::open};
  // The sets of closed contacts met at the current lambda, and whether switches at the
  // path's start are still proposed there.
  std::set<std::string> sets_at_lambda_;
  double sets_lambda_ = EventSource::none;
  bool switch_at_start_ = true;
  // Friction: where each contact last stuck, and the lambda at which the last contact was
  // taken as unstable (the contacts so taken are settling_.held()).
  std::map<std::int64_t, double> stuck_at_;
  double unstable_lambda_ = EventSource::none;
  // Notes where settling made contacts stick (stuck_at_).
  void note_sticks();
  static double window(double lambda) {
    return unstable_window * std::max(std::abs(lambda), 1e-6);
  }
};

}  // namespace latfrac
