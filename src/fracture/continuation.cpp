// The fixed-step fracture continuation: cascades, contacts and fragments.
#include "latfrac/fracture/continuation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "latfrac/base/error.h"
#include "latfrac/fracture/events.h"
#include "latfrac/solvers/nonlinear_path.h"
#include "latfrac/fracture/snapshot.h"

namespace latfrac {

FractureContinuation::FractureContinuation(Model& model, const Strength& strength,
                                           const Schedule& schedule,
                                           const SolverOptions& solver_options,
                                           EquilibriumSolver& solver, ProgressLine& progress)
    : model_(model),
      schedule_(schedule),
      solver_options_(solver_options),
      solver_(solver),
      progress_(progress),
      evaluator_(strength, model),
      fragments_(model) {
  if (solver_options.method == EquilibriumMethod::relaxation)
    relaxation_.emplace(model, solver_options);
  integrated_path_ = !model.law->is_linear();
}

// The safety net behind the support check: a piece held only by frictionless contacts
// (stiff along their normals alone) can still slide, which no connectivity check sees.
// When a factorization finds no stiffness, the unknown where it showed is held at its last
// known displacement (that one dof: a zero-energy mode is non-zero there, so holding it
// removes the mode, and holding the node's other axes could hold a direction in which the
// piece is supported), recorded as a one-node fragment, and the solve tried again
// (docs/robustness.md).
template <typename Solve>
auto FractureContinuation::holding_singular(double lambda, Solve solve) {
  for (std::int64_t attempt = 0;; ++attempt) {
    try {
      return solve();
    } catch (const SingularStiffness& singular) {
      if (singular.unknown() < 0 || attempt > model_.dofs.dof_count()) throw;
      std::int64_t dof = 0;
      while (dof < model_.dofs.dof_count() && model_.dofs.free_index[dof] != singular.unknown()) ++dof;
      if (dof == model_.dofs.dof_count()) throw;
      const FragmentDetector::LoosePart part{{dof / model_.dim()},
                                             {static_cast<int>(dof % model_.dim())}};
      const Vector last = state_.size() == model_.dofs.free_count ? model_.full_displacement(state_, lambda)
                                                                  : Vector::Zero(model_.dofs.dof_count());
      hold_part(model_, part, last);
      fragment_log_.push_back({lambda, 1});
      solver_.supports_changed();
      state_current_ = path_current_ = false;
      state_ = Vector();
    }
  }
}

void FractureContinuation::newton(double lambda) {
  if (state_.size() != model_.dofs.free_count) state_ = Vector::Zero(model_.dofs.free_count);
  holding_singular(lambda, [&] {
    if (state_.size() != model_.dofs.free_count) state_ = Vector::Zero(model_.dofs.free_count);
    return solver_.solve(lambda, state_);
  });
  state_lambda_ = lambda;
  state_current_ = true;
  path_current_ = false;
}

// The classical baseline: no factor and no affine path; every equilibrium is relaxed from
// the last one (whose prescribed dofs simply take their values at the new lambda).
void FractureContinuation::relax(double lambda) {
  // The last state is the starting guess (after a part was held, mapped onto the new
  // unknowns by hold_unsupported).
  if (state_.size() != model_.dofs.free_count) state_ = Vector::Zero(model_.dofs.free_count);
  const RelaxationReport report = relaxation_->solve(model_, lambda, state_);
  state_lambda_ = lambda;
  state_current_ = true;
  ++relaxation_solves_;
  relaxation_sweeps_ += report.sweeps;
  if (!report.converged) ++relaxation_unconverged_;
}

Vector FractureContinuation::displacement(double lambda) {
  if (state_current_ && lambda == state_lambda_) return model_.full_displacement(state_, lambda);
  if (relaxation_ || !model_.law->is_linear()) {
    relaxation_ ? relax(lambda) : newton(lambda);
    return model_.full_displacement(state_, lambda);
  }
  return model_.full_displacement(current_path(lambda).at(lambda), lambda);
}

Vector FractureContinuation::free_state(double lambda) {
  if (!(state_current_ && lambda == state_lambda_) && model_.law->is_linear() && !relaxation_) {
    return current_path(lambda).at(lambda);
  }
  displacement(lambda);  // brings state_ to lambda
  return state_;
}

const AffinePath& FractureContinuation::current_path(double lambda) {
  if (!path_current_) {
    path_ = holding_singular(lambda, [&] { return solver_.checked_affine_path(lambda); });
    path_current_ = true;
  }
  return path_;
}

void FractureContinuation::resolve(double lambda) {
  if (relaxation_ || !model_.law->is_linear()) {
    relaxation_ ? relax(lambda) : newton(lambda);
    path_current_ = false;
    return;
  }
  state_ = holding_singular(lambda, [&] { return solver_.checked_solve(lambda); });
  state_lambda_ = lambda;
  state_current_ = true;
  path_current_ = false;
}

bool FractureContinuation::hold_unsupported(const std::vector<FragmentDetector::LoosePart>& parts,
                                            double lambda) {
  if (parts.empty()) return false;
  const Vector u = displacement(lambda);
  for (const auto& part : parts) {
    hold_part(model_, part, u);
    fragment_log_.push_back({lambda, static_cast<std::int64_t>(part.nodes.size())});
  }
  solver_.supports_changed();
  state_current_ = path_current_ = false;  // the unknowns changed
  if (relaxation_) {
    state_.resize(model_.dofs.free_count);
    for (std::int64_t dof = 0; dof < model_.dofs.dof_count(); ++dof) {
      if (model_.dofs.free_index[dof] >= 0) state_[model_.dofs.free_index[dof]] = u[dof];
    }
  }
  return true;
}

void FractureContinuation::settle_contacts(double lambda) {
  // Switching thresholds of a millionth of a micron per metre of spacing keep roundoff
  // from toggling a contact that sits exactly at dn = 0.
  const double tolerance = 1e-12 * model_.lattice.spacing;
  std::set<std::vector<std::uint8_t>> visited;
  for (;;) {
    const Vector u = displacement(lambda);
    std::vector<std::pair<std::int64_t, bool>> switches;
    for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
      if (!model_.contact_capable(b)) continue;
      const double dn = model_.lattice.bond_direction[b].dot(model_.bond_displacement(u, b));
      if (model_.contact_active[b] && dn > tolerance) switches.push_back({b, false});
      if (!model_.contact_active[b] && dn < -tolerance) switches.push_back({b, true});
    }
    if (switches.empty()) return;
    // An active set met before means the iteration cycles (chattering): close every
    // contact that wants to close, open none, solve once and stop (docs/robustness.md).
    const bool cycling = !visited.insert(model_.contact_active).second;
    if (cycling) {
      std::erase_if(switches, [](const auto& s) { return !s.second; });
      ++chattering_resolved_;
      if (switches.empty()) return;
    }
    std::vector<std::int64_t> opened;
    for (const auto& [bond, close] : switches) {
      model_.contact_active[bond] = close;
      solver_.set_contact(bond, close);
      if (!close) opened.push_back(bond);
    }
    for (std::int64_t bond : opened)
      hold_unsupported(fragments_.unsupported_after_break(model_, bond), lambda);
    resolve(lambda);
    if (cycling) return;
  }
}

void FractureContinuation::break_bond(std::int64_t bond, const FailureIndex& failure, double lambda,
                                      std::int64_t cascade_id, RunResult& result) {
  const Vector u = displacement(lambda);
  model_.intact[bond] = 0;
  result.events.push_back(
      {lambda, bond, failure.value, static_cast<std::int8_t>(failure.mode), cascade_id});
  ++breaks_;
  // A bond that breaks in compression becomes a closed contact at once.
  const bool closes = model_.contact_capable(bond) && model_.lattice.bond_direction[bond].dot(
                                                          model_.bond_displacement(u, bond)) < 0;
  model_.contact_active[bond] = closes;
  if (!hold_unsupported(fragments_.unsupported_after_break(model_, bond), lambda)) {
    solver_.remove_bond(bond);
    if (closes) solver_.set_contact(bond, true);
  }
  resolve(lambda);
  if (model_.contact) settle_contacts(lambda);
  progress_.update(lambda, breaks_);
}

// A group of bonds tied for the largest f (within rounding) failed together: they break
// one after another, each followed by re-equilibration, without re-testing the others of
// the group (docs/robustness.md).
void FractureContinuation::break_group(const std::vector<CriticalBond>& group, double lambda,
                                       std::int64_t cascade_id, RunResult& result) {
  for (const CriticalBond& member : group) {
    if (model_.intact[member.bond])
      break_bond(member.bond, {member.index, member.mode}, lambda, cascade_id, result);
  }
}

void FractureContinuation::cascade(double lambda, RunResult& result, std::int64_t cascade_id) {
  for (;;) {
    const std::vector<CriticalBond> group =
        evaluator_.critical_group(model_, displacement(lambda), 1.0);
    if (group.empty()) return;
    if (cascade_id < 0) cascade_id = next_cascade_++;
    break_group(group, lambda, cascade_id, result);
  }
}

void FractureContinuation::start(RunResult& result) {
  // Pre-cut bonds are broken from the start: events of mode 2 at lambda 0, cascade 0.
  for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
    if (model_.precut[b])
      result.events.push_back({0.0, b, 0.0, static_cast<std::int8_t>(BreakMode::precut), 0});
  }
  solver_.stiffness_changed();
}

std::vector<double> FractureContinuation::snapshot_lambdas() const {
  std::vector<double> snapshots = schedule_.snapshots;
  if (snapshots.empty()) snapshots.push_back(schedule_.total);
  return snapshots;
}

void FractureContinuation::run_fixed_step(RunResult& result) {
  start(result);
  const double total = schedule_.total, increment = schedule_.stepping.increment;
  const long steps =
      total == 0 ? 0 : static_cast<long>(std::ceil(std::abs(total) / increment - 1e-9));
  const std::vector<double> snapshots = snapshot_lambdas();
  std::size_t next_snapshot = 0;
  for (long k = 0; k <= steps; ++k) {
    const double lambda = k == steps ? total : std::copysign(k * increment, total);
    if (model_.contact) settle_contacts(lambda);
    cascade(lambda, result);
    // A snapshot is taken at the first step that reaches its lambda.
    while (next_snapshot < snapshots.size() &&
           std::abs(snapshots[next_snapshot]) <= std::abs(lambda) + 1e-12) {
      result.snapshots.push_back(make_snapshot(model_, displacement(lambda), lambda, &evaluator_));
      ++next_snapshot;
    }
    progress_.update(lambda, breaks_);
  }
  result.fragments.insert(result.fragments.end(), fragment_log_.begin(), fragment_log_.end());
}

// From the equilibrium at lambda_c: the next event on the current affine path is the
// earliest of the next bond crossing, the next contact switch, and the end. At a
// crossing the bond that reached f = 1 breaks (explicitly: roundoff may leave its f a
// hair below 1), then the cascade runs at that lambda exactly as in the fixed-step method.
void FractureContinuation::run_event_driven(RunResult& result) {
  if (relaxation_) throw Error("run_event_driven: the relaxation solver has no affine path");
  if (integrated_path_) return run_integrated_events(result);
  start(result);
  const double total = schedule_.total;
  const std::vector<double> snapshots = snapshot_lambdas();
  std::size_t next_snapshot = 0;
  auto record_snapshots_until = [&](double lambda, bool inclusive) {
    while (next_snapshot < snapshots.size() &&
           (inclusive ? std::abs(snapshots[next_snapshot]) <= std::abs(lambda)
                      : std::abs(snapshots[next_snapshot]) < std::abs(lambda))) {
      const double at = snapshots[next_snapshot++];
      result.snapshots.push_back(make_snapshot(model_, displacement(at), at, &evaluator_));
    }
  };

  double lambda = 0;
  if (model_.contact) settle_contacts(lambda);
  cascade(lambda, result);
  // Contact switches at one lambda (ties, or a contact already at dn = 0) are taken one by
  // one. Should they come back to an active set met before at that lambda, they cycle:
  // the rest of the switches due there are left to settle_contacts, which ends cycles by
  // its own rule (docs/robustness.md).
  std::set<std::vector<std::uint8_t>> sets_at_lambda;
  double sets_lambda = std::numeric_limits<double>::quiet_NaN();
  bool switch_at_lambda = true;
  while (lambda != total) {
    const AffinePath& path = current_path(lambda);
    const PathCrossing crossing = next_break(model_, evaluator_, path, lambda, total);
    const PathCrossing contact =
        model_.contact ? next_contact_switch(model_, path, lambda, total, switch_at_lambda)
                       : PathCrossing{};
    const bool contact_first =
        contact.found() &&
        (!crossing.found() || std::abs(contact.lambda) < std::abs(crossing.lambda));
    const double next = contact_first ? contact.lambda : crossing.found() ? crossing.lambda : total;
    record_snapshots_until(next, false);
    if (next != sets_lambda) {
      sets_at_lambda.clear();
      sets_lambda = next;
      switch_at_lambda = true;
    }
    lambda = next;
    if (contact_first) {
      const bool close = !model_.contact_active[contact.bond];
      model_.contact_active[contact.bond] = close;
      solver_.set_contact(contact.bond, close);
      if (!close)
        hold_unsupported(fragments_.unsupported_after_break(model_, contact.bond), lambda);
      resolve(lambda);
      settle_contacts(lambda);
      cascade(lambda, result);
      if (!sets_at_lambda.insert(model_.contact_active).second) {
        switch_at_lambda = false;
        ++chattering_resolved_;
      }
    } else if (crossing.found()) {
      // Every bond that reached f = 1 at this lambda, within rounding, breaks now.
      const std::int64_t cascade_id = next_cascade_++;
      std::vector<double> index;
      std::vector<BreakMode> modes;
      evaluator_.evaluate(model_, displacement(lambda), index, modes);
      std::vector<CriticalBond> group;  // crossing.tied is in bond-id order
      for (std::int64_t bond : crossing.tied) group.push_back({bond, index[bond], modes[bond]});
      break_group(group, lambda, cascade_id, result);
      cascade(lambda, result, cascade_id);
    }
    progress_.update(lambda, breaks_);
  }
  record_snapshots_until(total, true);
  result.fragments.insert(result.fragments.end(), fragment_log_.begin(), fragment_log_.end());
}

// The general route (model.md section 5): from an equilibrium, CVODE follows the path to
// the next snapshot or the end and stops where a bond's f reaches 1; KINSOL puts the state
// on the path there. The bonds tied at that f (within 1e-9: the root is located to the
// solver's tolerance, not to rounding) break as a group, then the cascade runs. Contact
// switches are settled at breaks and snapshots, not located as events on this route.
void FractureContinuation::run_integrated_events(RunResult& result) {
  start(result);
  NonlinearPath path(model_, solver_, evaluator_, solver_options_);
  const double total = schedule_.total;
  const std::vector<double> snapshots = snapshot_lambdas();
  std::size_t next_snapshot = 0;
  double lambda = 0;
  if (model_.contact) settle_contacts(lambda);
  cascade(lambda, result);
  while (true) {
    while (next_snapshot < snapshots.size() &&
           std::abs(snapshots[next_snapshot]) <= std::abs(lambda)) {
      result.snapshots.push_back(make_snapshot(model_, displacement(lambda), lambda, &evaluator_));
      ++next_snapshot;
    }
    if (lambda == total) break;
    const double target = next_snapshot < snapshots.size() ? snapshots[next_snapshot] : total;
    Vector state = free_state(lambda);
    const PathEvent event = path.advance(lambda, target, state);
    lambda = event.bond >= 0 ? event.lambda : target;
    state_ = state;
    state_lambda_ = lambda;
    state_current_ = true;
    path_current_ = false;
    if (event.bond >= 0) {
      std::vector<CriticalBond> group =
          evaluator_.critical_group(model_, displacement(lambda), 1 - 1e-9);
      if (group.empty()) {
        const CriticalBond leader = evaluator_.most_critical(model_, displacement(lambda));
        group.push_back(leader);
      }
      break_group(group, lambda, next_cascade_++, result);
      cascade(lambda, result, next_cascade_ - 1);
    } else if (model_.contact) {
      // At a snapshot or the end: the contacts the path has crossed switch here.
      settle_contacts(lambda);
      cascade(lambda, result);
    }
    progress_.update(lambda, breaks_);
  }
  result.fragments.insert(result.fragments.end(), fragment_log_.begin(), fragment_log_.end());
}

}  // namespace latfrac
