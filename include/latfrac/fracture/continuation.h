// Fracture along the extension strain lambda: the paper's fixed-step algorithm, and the
// event-driven algorithm that locates each break exactly.
//
// lambda_k = k ds (the last step ends at loading.total). At each step: equilibrium, then
// the cascade { find the intact bond with the largest f; if f < 1 stop; break it;
// re-equilibrate at the same lambda }. With small kinematics the path between breaks is
// affine, so a step without a break needs no solve; a break downdates the factor and
// re-solves the two right-hand sides. With contact, each equilibrium is settled by an
// active-set iteration. Parts that a break leaves without support are held fixed.
#pragma once

#include <cstdint>
#include <optional>

#include "latfrac/fracture/schedule.h"
#include "latfrac/solvers/equilibrium.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/mechanics/fragments.h"
#include "latfrac/base/progress.h"
#include "latfrac/solvers/relaxation.h"
#include "latfrac/fracture/run_result.h"

namespace latfrac {

class FractureContinuation {
 public:
  // The model's supports must already hold every part that the pre-cuts cut loose
  // (prepare_supports, initial_supports.h).
  FractureContinuation(Model& model, const Strength& strength, const Schedule& schedule,
                       const SolverOptions& solver_options, EquilibriumSolver& solver,
                       ProgressLine& progress);

  // Runs from lambda = 0 to loading.total; appends events and snapshots to result.
  void run_fixed_step(RunResult& result);
  // The same with exact events: each break at the lambda where its bond reaches f = 1
  // (closed-form crossings on the affine path; docs/model.md, section 8).
  void run_event_driven(RunResult& result);

  // Follow paths with CVODE and KINSOL (docs/large-kinematics.md) even when the bond law
  // is linear and the closed-form route would serve: for comparing the two routes.
  void use_integrated_path(bool on) { integrated_path_ = on; }

  std::int64_t breaks() const { return breaks_; }
  // With solver.method = "relaxation": relaxation solves, their sweeps, and those that
  // stopped at the sweep cap before reaching the tolerance.
  std::int64_t relaxation_solves() const { return relaxation_solves_; }
  std::int64_t relaxation_sweeps() const { return relaxation_sweeps_; }
  std::int64_t relaxation_unconverged() const { return relaxation_unconverged_; }
  std::int64_t chattering_resolved() const { return chattering_resolved_; }

 private:
  // The full displacement at lambda: from the state of the current cascade when lambda
  // is its lambda, from the affine path otherwise.
  Vector displacement(double lambda);
  // Runs `solve`; where a factorization finds no stiffness, holds that node and retries.
  template <typename Solve>
  auto holding_singular(double lambda, Solve solve);
  // The free displacement at lambda, whichever way the state is computed.
  Vector free_state(double lambda);
  // The affine path of the current stiffness (solved, residual checked, when stale).
  const AffinePath& current_path(double lambda);
  // Re-equilibrates at lambda after the stiffness changed (one right-hand side).
  void resolve(double lambda);
  // Pre-cut events, the initial contact state, parts held from the start.
  void start(RunResult& result);
  std::vector<double> snapshot_lambdas() const;
  // Breaks until no intact bond has f >= 1 at lambda; a new cascade id unless given.
  void cascade(double lambda, RunResult& result, std::int64_t cascade_id = -1);
  // Breaks a group of tied bonds in its order (largest f, then lowest id).
  void break_group(const std::vector<CriticalBond>& group, double lambda, std::int64_t cascade_id,
                   RunResult& result);
  // Breaks one bond at lambda and re-equilibrates (contacts settled).
  void break_bond(std::int64_t bond, const FailureIndex& failure, double lambda,
                  std::int64_t cascade_id, RunResult& result);
  // Opens and closes contacts until every active one is in compression and every
  // inactive one is open.
  void settle_contacts(double lambda);
  // Holds each loose part along the axes it lacks (docs/robustness.md); true if any.
  bool hold_unsupported(const std::vector<FragmentDetector::LoosePart>& parts, double lambda);

  Model& model_;
  Schedule schedule_;
  SolverOptions solver_options_;
  EquilibriumSolver& solver_;
  ProgressLine& progress_;
  FailureEvaluator evaluator_;
  FragmentDetector fragments_;
  AffinePath path_;
  bool path_current_ = false;  // path_ describes the current stiffness
  Vector state_;               // free displacement at state_lambda_, when valid
  double state_lambda_ = 0;
  bool state_current_ = false;
  std::int64_t breaks_ = 0, chattering_resolved_ = 0;
  std::optional<RelaxationSolver> relaxation_;  // set when the scene asks for relaxation
  std::int64_t relaxation_solves_ = 0, relaxation_sweeps_ = 0, relaxation_unconverged_ = 0;
  // Relaxes the state to equilibrium at lambda, starting from the current state.
  void relax(double lambda);
  // Newton (KINSOL) to equilibrium at lambda from the current state: the nonlinear law.
  void newton(double lambda);
  // The event-driven loop on integrated (CVODE) paths.
  void run_integrated_events(RunResult& result);
  bool integrated_path_ = false;
  std::vector<FragmentEvent> fragment_log_;
  std::int64_t next_cascade_ = 1;
};

}  // namespace latfrac
