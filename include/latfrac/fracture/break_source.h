// Breaks as events: the first intact bond to reach f = 1 on the current affine path.
//
// Every bond's stresses are affine along the path (failure_evaluator.h), so each bond's
// crossing is found in closed form, or by bisection on the convex f of the critical-plane
// reading. The search runs in s = |lambda| so that compression (lambda < 0) reads like
// extension. Bonds reaching 1 at the same lambda within rounding (1e-12 relative) are
// tied and break together, in bond-id order (docs/robustness.md).
#pragma once

#include <cstdint>
#include <vector>

#include "latfrac/fracture/breaking.h"
#include "latfrac/fracture/event_source.h"
#include "latfrac/fracture/path_screen.h"

namespace latfrac {

// The first crossing on a path: its lambda and every bond tied at it, in bond-id order.
struct PathCrossing {
  double lambda = EventSource::none;
  std::vector<std::int64_t> tied;
  bool found() const { return !tied.empty(); }
};

// The first bonds to reach f = 1 after `from` and no later than `to`.
PathCrossing next_break(const Model& model, const FailureEvaluator& evaluator,
                        const AffinePath& path, double from, double to);
// The same on stresses already computed for the path (PathStressCache). A crossing after
// needed_until (NaN: none) cannot matter: the search may skip the bonds that cannot cross
// by then (with room for ties), and then returns a later crossing or none.
PathCrossing next_break(const Model& model, const FailureEvaluator& evaluator,
                        const PathStresses& stresses, double from, double to,
                        double needed_until = EventSource::none);
// The same among the listed intact bonds only (ascending ids), on one rank: `stresses`
// need hold only their nodes' stresses.
PathCrossing next_break_among(const Model& model, const FailureEvaluator& evaluator,
                              const PathStresses& stresses, const std::vector<std::int64_t>& bonds,
                              double from, double to, double needed_until);

// The stresses along the equilibrium's current path, computed once per path: the
// cascade's screen after a change (Breaking::screen) and the crossing search that follows
// read the same ones.
class PathStressCache {
 public:
  PathStressCache(EquilibriumState& equilibrium, const FailureEvaluator& evaluator)
      : equilibrium_(equilibrium), evaluator_(evaluator) {}
  // For the current path (at hand: equilibrium.path_at_hand()), searched in direction sign.
  const PathStresses& current(double lambda, double sign);
  // Whether current() would read them without a sweep.
  bool holds_current(double sign) const {
    return valid_ && version_ == equilibrium_.path_version() && sign_ == sign;
  }

 private:
  EquilibriumState& equilibrium_;
  const FailureEvaluator& evaluator_;
  bool valid_ = false;
  std::uint64_t version_ = 0;
  double sign_ = 0;
  PathStresses stresses_;
};

class BreakSource final : public EventSource {
 public:
  // With a cache, the search on the equilibrium's current path reads its stresses there;
  // with a screen as well, a path that follows a contact switch is searched only at the
  // bonds the screen cannot rule out (path_screen.h).
  BreakSource(EquilibriumState& equilibrium, const FailureEvaluator& evaluator, Breaking& breaking,
              PathStressCache* stresses = nullptr, PathScreen* screen = nullptr)
      : equilibrium_(equilibrium),
        evaluator_(evaluator),
        breaking_(breaking),
        stresses_(stresses),
        screen_(screen) {}
  double propose(const AffinePath& path, double from, double to, double needed_until) override;
  // The tied bonds break as a group (largest f first is not needed: their f are equal
  // within rounding), then the cascade runs at that lambda with the same cascade id.
  void take(double lambda) override;

 private:
  EquilibriumState& equilibrium_;
  const FailureEvaluator& evaluator_;
  Breaking& breaking_;
  PathStressCache* stresses_;
  PathScreen* screen_;
  PathCrossing proposed_;
};

}  // namespace latfrac
