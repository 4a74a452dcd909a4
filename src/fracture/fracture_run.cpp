// The three drivers of a fracture run: fixed steps, events on affine paths, events on
// integrated paths.
#include "latfrac/fracture/fracture_run.h"

#include <cmath>
#include <optional>

#include "latfrac/base/error.h"
#include "latfrac/base/parallel.h"
#include "latfrac/base/phase_times.h"
#include "latfrac/base/stop_signal.h"
#include "latfrac/fracture/break_source.h"
#include "latfrac/fracture/event_loop.h"
#include "latfrac/fracture/pair_switch_source.h"
#include "latfrac/solvers/nonlinear_path.h"

namespace latfrac {

FractureRun::FractureRun(Model& model, std::shared_ptr<const FailureCriterion> criterion,
                         BondStress reading, const Schedule& schedule,
                         const SolverOptions& options, EquilibriumSolver& solver,
                         ProgressLine& progress, RunResult& result)
    : model_(model),
      schedule_(schedule),
      options_(options),
      solver_(solver),
      progress_(progress),
      result_(result),
      evaluator_(std::move(criterion), reading, model),
      equilibrium_(model, solver, options),
      settling_(equilibrium_),
      breaking_(equilibrium_, settling_, evaluator_, progress, result),
      snapshots_(schedule.snapshots, schedule.total),
      integrated_(!model.is_linear()) {}

RunCounters FractureRun::counters() const {
  RunCounters counters;
  counters.breaks = breaking_.breaks();
  counters.contact_cycles = resumed_counts_.contact_cycles + settling_.cycles();
  counters.relaxation_sweeps = equilibrium_.relaxation_sweeps();
  counters.relaxation_unconverged = equilibrium_.relaxation_unconverged();
  counters.solves =
      resumed_counts_.solves + solver_.counters().solves + equilibrium_.relaxation_solves();
  counters.factorizations = resumed_counts_.factorizations + solver_.counters().factorizations;
  counters.factor_updates = resumed_counts_.factor_updates + solver_.counters().factor_updates;
  counters.floor_acceptances =
      resumed_counts_.floor_acceptances + solver_.counters().floor_acceptances;
  return counters;
}

// The model (pair states, supports) was restored before the solver was built; here the
// run's own state: counts, held parts, the equilibrium the next solve starts from, the
// snapshots taken. The fragments in `result` are those held before the run and during it.
void FractureRun::resume_from(const RunCheckpoint& checkpoint, const RunCounters& counts) {
  resumed_ = &checkpoint;
  resumed_counts_ = counts;
  resumed_counts_.breaks = 0;
  breaking_.restore(counts.breaks, checkpoint.next_cascade);
  const auto first_held = result_.fragments.begin() + checkpoint.fragments_at_start;
  equilibrium_.restore(checkpoint, {first_held, result_.fragments.end()}, counts);
  result_.fragments.erase(first_held, result_.fragments.end());
  snapshots_.restore(checkpoint.snapshots_taken);
}

void FractureRun::save_checkpoint(double lambda, std::int64_t next_step,
                                  const PairSwitchSource* switches, std::int64_t cascade) {
  RunCheckpoint checkpoint;
  checkpoint.started = true;
  checkpoint.lambda = lambda;
  checkpoint.next_step = next_step;
  checkpoint.cascade = cascade;
  for (PairState state : model_.pair_states())
    checkpoint.pair_states.push_back(static_cast<std::uint8_t>(state));
  for (const ContactMemory& m : model_.contact_memory()) {
    checkpoint.contact_memory.insert(checkpoint.contact_memory.end(),
                                     {m.anchor.x(), m.anchor.y(), m.anchor.z(), m.slip_direction.x(),
                                      m.slip_direction.y(), m.slip_direction.z(), m.normal, m.slip,
                                      m.work});
  }
  for (const Vec3& n : model_.contact_normal)
    checkpoint.contact_normals.insert(checkpoint.contact_normals.end(), {n.x(), n.y(), n.z()});
  checkpoint.free_index = model_.dofs().free_index;
  checkpoint.prescribed_base = model_.dofs().prescribed_base;
  checkpoint.prescribed_rate = model_.dofs().prescribed_rate;
  equilibrium_.save(checkpoint);
  checkpoint.factor = solver_.history();
  checkpoint.snapshots_taken = static_cast<std::int64_t>(snapshots_.taken());
  checkpoint.next_cascade = breaking_.next_cascade();
  if (switches) checkpoint.switches = switches->guard();
  // The file holds every part held so far; the run's own list is appended only at the end.
  const std::size_t at_start = result_.fragments.size();
  checkpoint.fragments_at_start = static_cast<std::int64_t>(at_start);
  result_.fragments.insert(result_.fragments.end(), equilibrium_.fragments().begin(),
                           equilibrium_.fragments().end());
  static_cast<RunCounters&>(result_.summary) = counters();
  result_.summary.final_lambda = lambda;
  result_.summary.complete = false;
  try {
    control_->save(result_, checkpoint);
  } catch (...) {
    result_.fragments.resize(at_start);
    throw;
  }
  result_.fragments.resize(at_start);
}

void FractureRun::between_events(double lambda, std::int64_t next_step,
                                 const PairSwitchSource* switches, std::int64_t cascade) {
  if (!control_) return;
  const bool stop = control_->stop_requested();
  if (stop || control_->checkpoint_due()) save_checkpoint(lambda, next_step, switches, cascade);
  if (stop) throw RunStopped();
}

void FractureRun::run() {
  if (!resumed_) start();
  if (model_.has_friction() && (integrated_ || !equilibrium_.affine()))
    throw Error("friction needs the exact affine path (small kinematics, the direct solver)");
  if (schedule_.stepping.method == SteppingMethod::fixed) {
    fixed_steps();
  } else if (integrated_) {
    integrated_events();
  } else {
    if (!equilibrium_.affine())
      throw Error("event-driven breaking needs the exact affine path (not relaxation)");
    event_driven();
  }
  finish();
}

// Pre-cut bonds are broken from the start: events of mode pre-cut at lambda 0, cascade 0.
void FractureRun::start() {
  for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
    if (model_.precut[b]) result_.events.push_back({0.0, b, 0.0, BreakMode::precut, 0});
  }
}

void FractureRun::finish() {
  result_.fragments.insert(result_.fragments.end(), equilibrium_.fragments().begin(),
                           equilibrium_.fragments().end());
  result_.contact_normal.clear();
  for (const Vec3& n : model_.contact_normal)
    result_.contact_normal.insert(result_.contact_normal.end(), {n.x(), n.y(), n.z()});
  if (model_.has_friction()) {
    equilibrium_.commit_contacts(schedule_.total);
    const auto& memory = model_.contact_memory();
    result_.contact_slip.resize(memory.size());
    result_.friction_work.resize(memory.size());
    result_.summary.contact_slip = result_.summary.friction_work = 0;
    for (std::size_t b = 0; b < memory.size(); ++b) {
      result_.contact_slip[b] = memory[b].slip;
      result_.friction_work[b] = memory[b].work;
      result_.summary.contact_slip += memory[b].slip;
      result_.summary.friction_work += memory[b].work;
    }
  }
}

void FractureRun::take_snapshot(double lambda) {
  const ScopedPhase phase(Phase::output);
  result_.snapshots.push_back(
      make_snapshot(model_, equilibrium_.displacement(lambda), lambda, &evaluator_));
}

// A snapshot is taken at the first step that reaches its lambda.
void FractureRun::fixed_steps() {
  const double total = schedule_.total, increment = schedule_.stepping.increment;
  const long steps = fixed_step_count(total, increment);
  const long first = resumed_ ? static_cast<long>(resumed_->next_step) : 0;
  std::int64_t unfinished = resumed_ ? resumed_->cascade : -1;
  resumed_ = nullptr;
  long k = first;
  breaking_.between_groups(
      [&](double lambda, std::int64_t cascade) { between_events(lambda, k, nullptr, cascade); });
  for (; k <= steps; ++k) {
    const double lambda = k == steps ? total : std::copysign(k * increment, total);
    if (unfinished < 0) settling_.settle(lambda);
    breaking_.cascade(lambda, unfinished, true);
    unfinished = -1;
    snapshots_.take_until(lambda, true, [&](double) { take_snapshot(lambda); }, 1e-12);
    progress_.update(lambda, breaking_.breaks());
    if (k < steps) between_events(lambda, k + 1);
  }
  breaking_.between_groups(nullptr);
}

// Breaks first, then contact switches: on a tie the break is taken.
void FractureRun::event_driven() {
  PathStressCache stresses(equilibrium_, evaluator_);
  std::optional<PathScreen> screen;
  if (screen_paths_ && PathScreen::applies(model_, evaluator_)) screen.emplace(model_, evaluator_);
  BreakSource breaks(equilibrium_, evaluator_, breaking_, &stresses, screen ? &*screen : nullptr);
  PairSwitchSource switches(equilibrium_, settling_);
  equilibrium_.want_paths(true);
  // After a change the new path is at hand, and the crossing search reads its stresses
  // next: the cascade's screen reads them first (FailureEvaluator::may_fail_at), and the
  // exact search runs only where a bond comes within 1e-9 of f = 1. The same events bit
  // for bit, for a fraction of a sweep where nothing breaks.
  const double sign = schedule_.total < 0 ? -1.0 : 1.0;  // the searches' direction
  breaking_.screen([&](double lambda) {
    return !equilibrium_.path_at_hand() ||
           evaluator_.may_fail_at(model_, stresses.current(lambda, sign), sign * lambda);
  });
  breaking_.between_groups(
      [&](double lambda, std::int64_t cascade) { between_events(lambda, 0, &switches, cascade); });
  double from = 0;
  if (resumed_) {
    from = resumed_->lambda;
    switches.restore(resumed_->switches);
    const std::int64_t unfinished = resumed_->cascade;
    resumed_ = nullptr;
    if (unfinished >= 0) breaking_.cascade(from, unfinished, true);
  } else {
    settling_.settle(0);
    breaking_.cascade(0, -1, true);
  }
  follow_events(
      equilibrium_, {&breaks, &switches}, from, schedule_.total,
      [&](double next) {
        snapshots_.take_until(next, false, [&](double at) { take_snapshot(at); });
      },
      [&](double lambda) {
        progress_.update(lambda, breaking_.breaks());
        if (lambda != schedule_.total) between_events(lambda, 0, &switches);
      });
  breaking_.between_groups(nullptr);
  breaking_.screen(nullptr);
  if (screen) {
    screened_searches_ = screen->screened_searches();
    full_searches_ = screen->full_searches();
  }
  snapshots_.take_until(schedule_.total, true, [&](double at) { take_snapshot(at); });
}

// The general route (model.md section 5): from an equilibrium, CVODE follows the path to
// the next snapshot or the end and stops where a bond's f reaches 1; KINSOL puts the state
// on the path there. The bonds tied at that f (within 1e-9: the root is located to the
// solver's tolerance, not to rounding) break as a group, then the cascade runs. Contact
// switches are settled at breaks and snapshots, not located as events on this route.
void FractureRun::integrated_events() {
  NonlinearPath path(model_, solver_, evaluator_, options_);
  const double total = schedule_.total;
  double lambda = 0;
  if (resumed_) {
    lambda = resumed_->lambda;
    resumed_ = nullptr;
  } else {
    settling_.settle(lambda);
    breaking_.cascade(lambda);
  }
  while (true) {
    snapshots_.take_until(lambda, true, [&](double) { take_snapshot(lambda); });
    if (lambda == total) break;
    const double target = snapshots_.next_or(total);
    Vector state = equilibrium_.free_state(lambda);
    const PathEvent event = path.advance(lambda, target, state);
    lambda = event.bond >= 0 ? event.lambda : target;
    equilibrium_.adopt(state, lambda);
    if (event.bond >= 0) {
      std::vector<CriticalBond> group =
          evaluator_.critical_group(model_, equilibrium_.displacement(lambda), 1 - 1e-9);
      if (group.empty()) group.push_back(evaluator_.most_critical(model_, equilibrium_.displacement(lambda)));
      const std::int64_t cascade_id = breaking_.new_cascade();
      breaking_.break_group(group, lambda, cascade_id);
      breaking_.cascade(lambda, cascade_id);
    } else if (model_.has_contact()) {
      // At a snapshot or the end: the contacts the path has crossed switch here.
      settling_.settle(lambda);
      breaking_.cascade(lambda);
    }
    progress_.update(lambda, breaking_.breaks());
    if (lambda != total) between_events(lambda, 0);
  }
}

bool RankedControl::stop_requested() const {
  return parallel::any_rank(writer_ ? writer_->stop_requested() : latfrac::stop_requested());
}

bool RankedControl::checkpoint_due() {
  return parallel::any_rank(writer_ && writer_->checkpoint_due());
}

void RankedControl::save(RunResult& result, RunCheckpoint& checkpoint) {
  const ScopedPhase phase(Phase::output);
  if (writer_) writer_->save(result, checkpoint);
}

}  // namespace latfrac
