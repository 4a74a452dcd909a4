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

class BreakSource final : public EventSource {
 public:
  BreakSource(EquilibriumState& equilibrium, const FailureEvaluator& evaluator, Breaking& breaking)
      : equilibrium_(equilibrium), evaluator_(evaluator), breaking_(breaking) {}
  double propose(const AffinePath& path, double from, double to) override;
  // The tied bonds break as a group (largest f first is not needed: their f are equal
  // within rounding), then the cascade runs at that lambda with the same cascade id.
  void take(double lambda) override;

 private:
  EquilibriumState& equilibrium_;
  const FailureEvaluator& evaluator_;
  Breaking& breaking_;
  PathCrossing proposed_;
};

}  // namespace latfrac
