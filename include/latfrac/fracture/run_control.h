// Checkpoints and clean stops of a fracture run: the state saved between events, and the
// object that decides when to save and whether to stop.
//
// Between two events (fixed steps: after a step, or after a break inside its cascade;
// event-driven: after an event, or after a break inside the cascade that follows a break;
// integrated: after a path segment and its cascade) the run's state is fully
// described by the pair states, the supports (the parts held so far, with the
// displacements they are held at), the equilibrium state the next solve starts from, the
// counters and the position in the schedule. A RunCheckpoint holds exactly that; with the
// events and snapshots so far (the RunResult) it continues the run as if it had never
// stopped: the same events in the same order, lambdas equal up to the rounding of a fresh
// factorization (docs/restart.md). Nothing in a run draws random numbers, so there is no
// generator state to keep (heterogeneity's seed is used when the model is built).
#pragma once

#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "latfrac/fracture/run_result.h"
#include "latfrac/solvers/equilibrium.h"

namespace latfrac {

// The guard of the contact-switch source against cycling at one lambda
// (pair_switch_source.h): the sets of closed contacts met at `lambda`.
struct SwitchGuard {
  double lambda = std::numeric_limits<double>::quiet_NaN();
  bool switch_at_start = true;
  std::vector<std::string> sets;  // each one byte per bond (pair_settling.h, closed_pairs)
  // Friction: where contacts last stuck (bond, lambda), and the contacts taken as unstable
  // with the lambda at which the last one was (pair_switch_source.h).
  std::vector<std::int64_t> stuck_bonds;
  std::vector<double> stuck_lambdas;
  std::vector<std::int64_t> unstable;
  double unstable_lambda = std::numeric_limits<double>::quiet_NaN();
};

struct RunCheckpoint {
  // False: written before the run began (a resume starts from lambda = 0).
  bool started = false;
  double lambda = 0;           // every event up to and at lambda has been taken
  std::int64_t next_step = 0;  // fixed steps: the index k of the next step
  // Stopped inside this cascade (its id) at lambda, after a group of breaks: the resume
  // finishes it first (fixed steps: it belongs to step next_step). -1: between events.
  std::int64_t cascade = -1;
  std::vector<std::uint8_t> pair_states;  // per bond, PairState
  // With friction, per bond, its contact's memory (ContactMemory): anchor (3), slip
  // direction (3), normal, slip, work; empty without friction.
  std::vector<double> contact_memory;
  static constexpr int memory_values = 9;
  // With contacts along cracks (contact.normal = "crack"), per bond the normal its contact
  // acts along (3 values); empty otherwise.
  std::vector<double> contact_normals;
  // The supports (mechanics/supports.h): per dof, free index or -1, base and rate.
  std::vector<std::int64_t> free_index;
  std::vector<double> prescribed_base, prescribed_rate;
  // The equilibrium state (free dofs) the next solve starts from, its lambda, and
  // whether it is the equilibrium at that lambda.
  std::vector<double> free_state;
  double state_lambda = 0;
  bool state_valid = false;
  // How the solver's factor came about (so that a resume rebuilds it bit for bit).
  EquilibriumSolver::History factor;
  std::int64_t snapshots_taken = 0;
  std::int64_t next_cascade = 1;
  std::int64_t fragments_at_start = 0;  // of the result's fragments, those held before the run
  SwitchGuard switches;
  // How the run was started, for a resume: the problem file and the --set overrides.
  std::string problem_path;
  std::vector<std::string> overrides;
};

// What a run asks between events. The run calls save() when checkpoint_due() or
// stop_requested() says so, then stops (throws RunStopped) if a stop was requested.
class RunControl {
 public:
  virtual ~RunControl() = default;
  virtual bool stop_requested() const = 0;
  virtual bool checkpoint_due() = 0;
  // Writes the results so far (result.summary.complete is false) with the checkpoint.
  // Throws Error when it cannot write; the last checkpoint written stays as it was.
  virtual void save(RunResult& result, RunCheckpoint& checkpoint) = 0;
};

// The control of a run under MPI (the petsc backend, docs/parallel.md): every rank takes
// the same steps, so a stop and a checkpoint are decided for all ranks at once (a stop
// signal on any rank stops every rank; rank 0's clock says when a checkpoint is due) and
// only rank 0, which holds the writer, writes. With one rank it is the writer itself.
class RankedControl : public RunControl {
 public:
  // writer: the result file's writer on rank 0, null on the others.
  explicit RankedControl(RunControl* writer) : writer_(writer) {}
  bool stop_requested() const override;
  bool checkpoint_due() override;
  void save(RunResult& result, RunCheckpoint& checkpoint) override;

 private:
  RunControl* writer_;
};

// Thrown out of a run that stopped on request, after its checkpoint was saved.
class RunStopped : public std::exception {
 public:
  const char* what() const noexcept override { return "the run stopped on request"; }
};

}  // namespace latfrac
