// A fracture run along the extension strain lambda: the paper's fixed-step algorithm, the
// event-driven algorithm that locates each event exactly, and the event-driven algorithm
// on integrated (CVODE) paths for a nonlinear law (model.md section 5).
//
//   fixed-step     lambda_k = k ds (the last step ends at the total). At each step the
//                  contacts settle, then the cascade breaks every bond with f >= 1.
//   event-driven   from an equilibrium, every event source (break_source.h,
//                  pair_switch_source.h) proposes its first event on the current affine
//                  path; the earliest is taken, then the cascade runs at its lambda.
//   integrated     CVODE follows the nonlinear path and stops where a bond reaches f = 1
//                  (solvers/nonlinear_path.h); contacts settle at breaks and snapshots.
// The pieces: the equilibrium and its caches (equilibrium_state.h), the contacts' settling
// (pair_settling.h), breaking and cascades (breaking.h), the snapshots (snapshots.h).
#pragma once

#include <memory>
#include <vector>

#include "latfrac/base/progress.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/fracture/breaking.h"
#include "latfrac/fracture/equilibrium_state.h"
#include "latfrac/fracture/pair_settling.h"
#include "latfrac/fracture/pair_switch_source.h"
#include "latfrac/fracture/run_control.h"
#include "latfrac/fracture/run_result.h"
#include "latfrac/fracture/schedule.h"
#include "latfrac/fracture/snapshots.h"

namespace latfrac {

class FractureRun {
 public:
  // The model's supports must already hold every part that the pre-cuts cut loose
  // (prepare_supports, initial_supports.h). Events and snapshots go into `result`.
  FractureRun(Model& model, std::shared_ptr<const FailureCriterion> criterion,
              BondStress reading, const Schedule& schedule, const SolverOptions& options,
              EquilibriumSolver& solver, ProgressLine& progress, RunResult& result);

  // Runs from lambda = 0 (or from the checkpoint given to resume_from) to the schedule's
  // total, by its stepping method. With a control, between events it saves checkpoints
  // when they are due and, when a stop is requested, saves one and throws RunStopped.
  void run();
  void set_control(RunControl* control) { control_ = control; }
  // Continue from a checkpoint (run_control.h): `result` already holds the events and
  // snapshots up to it, and the model its pair states and supports; `counts` are the
  // counters the run had reached.
  void resume_from(const RunCheckpoint& checkpoint, const RunCounters& counts);
  // Follow paths with CVODE and KINSOL (docs/large-kinematics.md) even when the bond law
  // is linear and the closed-form route would serve: for comparing the two routes.
  void use_integrated_path(bool on) { integrated_ = on; }
  // Search every event-driven path in full (on: screened where it applies, the default;
  // path_screen.h). The events are the same either way: for comparing the two.
  void screen_paths(bool on) { screen_paths_ = on; }
  // Of the event-driven crossing searches on the current path, how many the screen
  // answered and how many were made in full beside it (both 0 without it).
  std::int64_t screened_searches() const { return screened_searches_; }
  std::int64_t full_searches() const { return full_searches_; }

  // What the run counted, the solver's work included.
  RunCounters counters() const;

 private:
  void start();
  void fixed_steps();
  void event_driven();
  void integrated_events();
  // Between two events: a checkpoint if one is due or a stop is asked for, then the stop.
  void between_events(double lambda, std::int64_t next_step,
                      const PairSwitchSource* switches = nullptr, std::int64_t cascade = -1);
  void save_checkpoint(double lambda, std::int64_t next_step, const PairSwitchSource* switches,
                       std::int64_t cascade);
  void take_snapshot(double lambda);
  void finish();

  Model& model_;
  Schedule schedule_;
  SolverOptions options_;
  EquilibriumSolver& solver_;
  ProgressLine& progress_;
  RunResult& result_;
  FailureEvaluator evaluator_;
  EquilibriumState equilibrium_;
  PairSettling settling_;
  Breaking breaking_;
  SnapshotSchedule snapshots_;
  bool integrated_ = false;
  bool screen_paths_ = true;
  std::int64_t screened_searches_ = 0, full_searches_ = 0;
  RunControl* control_ = nullptr;
  const RunCheckpoint* resumed_ = nullptr;  // set by resume_from until run() starts
  RunCounters resumed_counts_;              // the solver's counts before the resume
};

}  // namespace latfrac
