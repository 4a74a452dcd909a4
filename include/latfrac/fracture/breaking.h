// Breaking bonds at a fixed lambda: one bond, a group of tied bonds, and the cascade.
//
// A break records its event, puts the bond into its broken state (a closed contact when
// it breaks in compression in a scene with contact, open otherwise), re-equilibrates and
// settles the contacts. A cascade at lambda breaks, one at a time, the intact bonds tied
// for the largest f until none has f >= 1 (model.md section 5; ties: docs/robustness.md).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "latfrac/base/progress.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/fracture/equilibrium_state.h"
#include "latfrac/fracture/pair_settling.h"
#include "latfrac/fracture/run_result.h"

namespace latfrac {

class Breaking {
 public:
  Breaking(EquilibriumState& equilibrium, PairSettling& settling,
           const FailureEvaluator& evaluator, ProgressLine& progress, RunResult& result)
      : equilibrium_(equilibrium),
        settling_(settling),
        evaluator_(evaluator),
        progress_(progress),
        result_(result) {}

  // A new cascade id (cascade 0 holds the pre-cuts).
  std::int64_t new_cascade() { return next_cascade_++; }
  // Breaks one bond at lambda and re-equilibrates (contacts settled).
  void break_bond(std::int64_t bond, const FailureIndex& failure, double lambda,
                  std::int64_t cascade_id);
  // Breaks a group of bonds that failed together, in its order (bond id), each followed
  // by re-equilibration, without testing the others of the group again.
  void break_group(const std::vector<CriticalBond>& group, double lambda, std::int64_t cascade_id);
  // Breaks until no intact bond has f >= 1 at lambda; a new cascade id unless one is given.
  // With may_stop, calls the hook set by between_groups() after each group: where a run
  // can save a checkpoint and stop inside a long cascade (run_control.h).
  void cascade(double lambda, std::int64_t cascade_id = -1, bool may_stop = false);
  void between_groups(std::function<void(double lambda, std::int64_t cascade_id)> hook) {
    between_groups_ = std::move(hook);
  }
  // A cheap test run before each search of the cascade: when it says no bond can have
  // f >= 1 at lambda, the cascade ends without the exact search (which would find none).
  void screen(std::function<bool(double lambda)> may_break) { may_break_ = std::move(may_break); }

  std::int64_t breaks() const { return breaks_; }
  std::int64_t next_cascade() const { return next_cascade_; }
  // A resumed run's counts (run_control.h).
  void restore(std::int64_t breaks, std::int64_t next_cascade) {
    breaks_ = breaks;
    next_cascade_ = next_cascade;
  }

 private:
  EquilibriumState& equilibrium_;
  PairSettling& settling_;
  const FailureEvaluator& evaluator_;
  ProgressLine& progress_;
  RunResult& result_;
  std::int64_t breaks_ = 0;
  std::int64_t next_cascade_ = 1;
  std::function<void(double, std::int64_t)> between_groups_;
  std::function<bool(double)> may_break_;
};

}  // namespace latfrac
