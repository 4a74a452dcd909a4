// The equilibrium of a fracture run: its method, its caches, and the changes of the model.
#include "latfrac/fracture/equilibrium_state.h"

#include <cmath>
#include <string>

#include "latfrac/base/error.h"
#include "latfrac/base/phase_times.h"

namespace latfrac {

EquilibriumState::EquilibriumState(Model& model, EquilibriumSolver& solver,
                                   const SolverOptions& options)
    : model_(model), solver_(solver), fragments_detector_(model) {
  if (options.method == EquilibriumMethod::relaxation) relaxation_.emplace(options);
}

// The safety net behind the support check: a piece held only by frictionless contacts
// (stiff along their normals alone) can still slide, which no connectivity check sees.
// When a factorization finds no stiffness, the unknown where it showed is held at its last
// known displacement (that one dof: a zero-energy mode is non-zero there, so holding it
// removes the mode, and holding the node's other axes could hold a direction in which the
// piece is supported), recorded as a one-node fragment, and the solve tried again
// (docs/robustness.md).
template <typename Solve>
auto EquilibriumState::holding_singular(double lambda, Solve solve) {
  const DofMap& dofs = model_.dofs();
  for (std::int64_t attempt = 0;; ++attempt) {
    try {
      return solve();
    } catch (const SingularStiffness& singular) {
      if (singular.unknown() < 0 || attempt > dofs.dof_count()) throw;
      std::int64_t dof = 0;
      while (dof < dofs.dof_count() && dofs.free_index[dof] != singular.unknown()) ++dof;
      if (dof == dofs.dof_count()) throw;
      const Vector last = state_.size() == dofs.free_count
                              ? model_.full_displacement(state_, lambda)
                              : Vector::Zero(dofs.dof_count());
      solver_.hold({{{dof / model_.dim()}, {static_cast<int>(dof % model_.dim())}}}, last);
      fragments_.push_back({lambda, 1});
      invalidate();
      state_ = Vector();
    }
  }
}

void EquilibriumState::newton(double lambda) {
  const std::int64_t unknowns = model_.dofs().free_count;
  if (state_.size() != unknowns) state_ = Vector::Zero(unknowns);
  holding_singular(lambda, [&] {
    if (state_.size() != model_.dofs().free_count) state_ = Vector::Zero(model_.dofs().free_count);
    return solver_.solve(lambda, state_);
  });
  state_lambda_ = lambda;
  state_valid_ = true;
  path_valid_ = false;
}

// The classical baseline: no factor and no affine path; every equilibrium is relaxed from
// the last one (whose prescribed dofs simply take their values at the new lambda).
void EquilibriumState::relax(double lambda) {
  // The last state is the starting guess (after a part was held, mapped onto the new
  // unknowns by hold()).
  if (state_.size() != model_.dofs().free_count) state_ = Vector::Zero(model_.dofs().free_count);
  const RelaxationReport report = relaxation_->solve(model_, lambda, state_);
  // A state that is not finite must not reach a criterion: the run stops here, its last
  // checkpoint intact, instead of carrying NaN into the events.
  if (!std::isfinite(report.relative_residual) || !state_.allFinite()) {
    throw Error("the relaxation diverged at lambda = " + std::to_string(lambda) + " (after " +
                std::to_string(report.sweeps) +
                " sweeps its residual is not a finite number); solver.method = \"newton\" "
                "solves the same equilibrium directly");
  }
  state_lambda_ = lambda;
  state_valid_ = true;
  ++relaxation_solves_;
  relaxation_sweeps_ += report.sweeps;
  if (!report.converged) ++relaxation_unconverged_;
}

Vector EquilibriumState::displacement(double lambda) {
  if (state_valid_ && lambda == state_lambda_) return model_.full_displacement(state_, lambda);
  if (!affine()) {
    relaxation_ ? relax(lambda) : newton(lambda);
    return model_.full_displacement(state_, lambda);
  }
  return model_.full_displacement(path(lambda).at(lambda), lambda);
}

Vector EquilibriumState::free_state(double lambda) {
  if (!(state_valid_ && lambda == state_lambda_) && affine()) return path(lambda).at(lambda);
  displacement(lambda);  // brings state_ to lambda
  return state_;
}

const AffinePath& EquilibriumState::path(double lambda) {
  if (!path_valid_) {
    path_ = holding_singular(lambda, [&] { return solver_.checked_affine_path(lambda); });
    path_valid_ = true;
    ++path_version_;
  }
  return path_;
}

void EquilibriumState::resolve(double lambda) {
  if (!affine()) {
    relaxation_ ? relax(lambda) : newton(lambda);
    path_valid_ = false;
    return;
  }
  if (paths_wanted_) {
    // The event loop asks for the path at this lambda next: one solve with both load
    // columns gives it, and the state on it, instead of a solve for the state and another
    // for the path.
    path_ = holding_singular(lambda, [&] { return solver_.checked_affine_path(lambda); });
    path_valid_ = true;
    ++path_version_;
    state_ = path_.at(lambda);
  } else {
    state_ = holding_singular(lambda, [&] { return solver_.checked_solve(lambda); });
    path_valid_ = false;
  }
  state_lambda_ = lambda;
  state_valid_ = true;
}

void EquilibriumState::hold(const std::vector<FragmentDetector::LoosePart>& parts, double lambda,
                            const Vector& before) {
  if (parts.empty()) return;
  std::vector<EquilibriumSolver::Hold> holds;
  for (const auto& part : parts) {
    holds.push_back({part.nodes, part.free_components});
    fragments_.push_back({lambda, static_cast<std::int64_t>(part.nodes.size())});
  }
  solver_.hold(holds, before);
  invalidate();  // the unknowns changed
  if (relaxation_) state_ = model_.free_part(before);
}

void EquilibriumState::commit_at(const Vector& displacement) {
  const ScopedPhase phase(Phase::contacts);
  if (!model_.has_friction()) return;
  const InteractionLaw& law = *model_.contact_law();
  for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
    if (!model_.contact_capable(b)) continue;
    solver_.set_contact_memory(b, law.advanced(model_.springs(b), model_.state(b),
                                               model_.bond_displacement(displacement, b)));
  }
}

void EquilibriumState::commit_contacts(double lambda) { commit_at(displacement(lambda)); }

void EquilibriumState::change_pairs(const std::vector<PairChange>& changes, double lambda,
                                    const Vector& before) {
  commit_at(before);
  std::vector<std::int64_t> disconnected;
  for (const PairChange& change : changes) {
    const PairState state = model_.state(change.bond);
    if (model_.has_friction() && model_.can_touch(change.bond)) {
      solver_.set_contact_memory(
          change.bond, model_.contact_law()->entered(
                           model_.contact_springs(change.bond), state, change.state,
                           model_.bond_displacement(before, change.bond), change.direction));
    }
    solver_.set_pair_state(change.bond, change.state);
    if (connects(state) && !connects(change.state)) disconnected.push_back(change.bond);
  }
  for (std::int64_t bond : disconnected)
    hold(fragments_detector_.unsupported_after_break(model_, bond), lambda, before);
  resolve(lambda);
  if (model_.has_friction()) commit_at(model_.full_displacement(state_, lambda));
}

void EquilibriumState::adopt(const Vector& free_state, double lambda) {
  state_ = free_state;
  state_lambda_ = lambda;
  state_valid_ = true;
  path_valid_ = false;
}

void EquilibriumState::save(RunCheckpoint& checkpoint) const {
  checkpoint.free_state.assign(state_.data(), state_.data() + state_.size());
  checkpoint.state_lambda = state_lambda_;
  checkpoint.state_valid = state_valid_;
}

void EquilibriumState::restore(const RunCheckpoint& checkpoint,
                               const std::vector<FragmentEvent>& held, const RunCounters& counts) {
  fragments_ = held;
  state_ = Eigen::Map<const Vector>(checkpoint.free_state.data(),
                                    static_cast<Eigen::Index>(checkpoint.free_state.size()));
  state_lambda_ = checkpoint.state_lambda;
  state_valid_ = checkpoint.state_valid && state_.size() == model_.dofs().free_count;
  path_valid_ = false;
  relaxation_sweeps_ = counts.relaxation_sweeps;
  relaxation_unconverged_ = counts.relaxation_unconverged;
}

}  // namespace latfrac
