// The linear path of the equilibrium solver: the factor, its rank updates when bonds break
// and contacts switch, checked solves and affine paths, and the correction re-solves.
// KINSOL's Newton iteration is in equilibrium_newton.cpp.
#include "latfrac/solvers/equilibrium.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "latfrac/base/error.h"

namespace latfrac {

void EquilibriumSolver::update_loads() {
  if (loads_current_) return;
  const Vector zero = Vector::Zero(model_.dofs().free_count);
  const Vector at0 = model_.internal_force(model_.full_displacement(zero, 0.0), boundary_bonds_);
  const Vector at1 = model_.internal_force(model_.full_displacement(zero, 1.0), boundary_bonds_);
  load0_ = model_.free_part(model_.external_force - at0);
  load1_ = model_.free_part(at0 - at1);
  loads_current_ = true;
}

double EquilibriumSolver::load_scale(double lambda) {
  update_loads();
  return max_abs(load0_ + lambda * load1_);
}

void EquilibriumSolver::refactorize(const Vector& free_displacement, double lambda) {
  if (model_.dofs().free_count == 0) {
    factor_current_ = true;
    return;
  }
  last_solution_valid_ = false;
  stiffness_.assemble(model_, model_.full_displacement(free_displacement, lambda));
  factor_.factorize(stiffness_);
  ++counters_.factorizations;
  factor_current_ = true;
  updates_since_factorization_ = 0;
  factored_states_.resize(model_.pair_states().size());
  for (std::size_t b = 0; b < factored_states_.size(); ++b)
    factored_states_[b] = static_cast<std::uint8_t>(model_.pair_states()[b]);
  changes_since_factorization_.clear();
}

EquilibriumSolver::History EquilibriumSolver::history() const {
  History h;
  // Only a factor of the linear stiffness (refactorize) has a history to replay; a
  // resume otherwise starts from a fresh factorization.
  h.factor_current = factor_current_ && model_.dofs().free_count > 0 &&
                     factored_states_.size() == model_.pair_states().size();
  if (h.factor_current) {
    h.factored_states = factored_states_;
    h.changes = changes_since_factorization_;
  }
  h.solution_valid = last_solution_valid_;
  if (last_solution_valid_) {
    h.solution_lambda = last_lambda_;
    h.solution = last_solution_;
    h.pending_forces = pending_forces_;
  }
  return h;
}

void EquilibriumSolver::rebuild(const History& history, const std::vector<PairState>& states) {
  if (history.factor_current) {
    refactorize(Vector::Zero(model_.dofs().free_count), 0.0);
    for (const auto& [bond, state] : history.changes)
      set_pair_state(bond, static_cast<PairState>(state));
  }
  for (std::size_t b = 0; b < states.size(); ++b) {
    if (model_.state(static_cast<std::int64_t>(b)) == states[b]) continue;
    if (history.factor_current)
      throw Error("a checkpoint's factor history does not lead to its pair states");
    editor_.set_state(static_cast<std::int64_t>(b), states[b]);
  }
  loads_current_ = false;
  if (history.solution_valid) {
    last_solution_ = history.solution;
    last_lambda_ = history.solution_lambda;
    last_solution_valid_ = true;
    pending_forces_ = history.pending_forces;
  }
  counters_ = {};
}

void EquilibriumSolver::update_factor(std::int64_t bond, const std::vector<RankOneTerm>& terms,
                                      bool downdate) {
  loads_current_ = false;
  if (!factor_current_) return;  // the next factorization assembles the new stiffness
  if (updates_since_factorization_ >= options_.refactor_every) {
    factor_current_ = false;
    last_solution_valid_ = false;
    return;
  }
  std::vector<CholeskyFactor::Column> columns;
  for (const auto& [weight, direction] : terms) {
    if (weight <= 0) continue;
    CholeskyFactor::Column column;
    append_on_bond(bond, std::sqrt(weight) * direction, column);
    if (!column.empty()) columns.push_back(std::move(column));
  }
  try {
    factor_.update(columns, downdate);
  } catch (const Error&) {
    factor_current_ = false;  // refactorize; a real singularity is reported there
    last_solution_valid_ = false;
    return;
  }
  ++counters_.factor_updates;
  ++updates_since_factorization_;
  if (last_solution_valid_) record_force_change(bond, terms, downdate);
}

void EquilibriumSolver::remember_solution(const Vector& free_displacement, double lambda) {
  last_solution_ = free_displacement;
  last_lambda_ = lambda;
  last_solution_valid_ = true;
  pending_forces_.clear();
}

// The spring sum_k w_k d_k d_k' between the bond's nodes carried the internal force
// f = sum_k w_k (d_k . (u_j - u_i)) d_k on node j (and -f on node i) in the last solution.
// Removing it leaves the residual R = internal - external short by f, so the correction
// solves K du = f at j, -f at i; adding a spring (a contact closing) is the opposite.
void EquilibriumSolver::record_force_change(std::int64_t bond,
                                            const std::vector<RankOneTerm>& terms,
                                            bool downdate) {
  const Bond& pair = model_.lattice.bonds[bond];
  const std::vector<int> axes = model_.lattice.axes();
  const int dim = model_.dim();
  auto displacement = [&](std::int64_t node, int c) {
    const std::int64_t dof = node * dim + c;
    const std::int64_t f = model_.dofs().free_index[dof];
    return f >= 0 ? last_solution_[f]
                  : model_.dofs().prescribed_base[dof] + last_lambda_ * model_.dofs().prescribed_rate[dof];
  };
  Vec3 stretch = Vec3::Zero();  // u_j - u_i on the lattice's axes
  for (int c = 0; c < dim; ++c)
    stretch[axes[c]] = displacement(pair.j, c) - displacement(pair.i, c);
  Vec3 force = Vec3::Zero();
  for (const auto& [weight, direction] : terms) force += weight * direction.dot(stretch) * direction;
  append_on_bond(bond, downdate ? force : Vec3(-force), pending_forces_);
}

void EquilibriumSolver::append_on_bond(std::int64_t bond, const Vec3& v,
                                       CholeskyFactor::Column& column) const {
  const Bond& pair = model_.lattice.bonds[bond];
  const std::vector<int> axes = model_.lattice.axes();
  const int dim = model_.dim();
  for (int c = 0; c < dim; ++c) {
    const double value = v[axes[c]];
    if (value == 0) continue;
    const std::int64_t fj = model_.dofs().free_index[pair.j * dim + c];
    const std::int64_t fi = model_.dofs().free_index[pair.i * dim + c];
    if (fj >= 0) column.push_back({fj, value});
    if (fi >= 0) column.push_back({fi, -value});
  }
}

// The old state's terms come out first, then the new state's go in: two updates, each
// counted (a break into a closed contact is a downdate of the bond and an update of the
// contact spring).
void EquilibriumSolver::set_pair_state(std::int64_t bond, PairState state) {
  if (model_.state(bond) == state) return;
  if (factor_current_)
    changes_since_factorization_.push_back({bond, static_cast<std::uint8_t>(state)});
  const PairSprings springs = model_.springs(bond);
  const InteractionLaw* old_law = model_.law_of(bond);
  const std::vector<RankOneTerm> removed =
      old_law ? old_law->stiffness_terms(springs, model_.state(bond)) : std::vector<RankOneTerm>{};
  editor_.set_state(bond, state);
  const InteractionLaw* new_law = model_.law_of(bond);
  const std::vector<RankOneTerm> added =
      new_law ? new_law->stiffness_terms(springs, state) : std::vector<RankOneTerm>{};
  if (!removed.empty()) update_factor(bond, removed, /*downdate=*/true);
  if (!added.empty()) update_factor(bond, added, /*downdate=*/false);
}

void EquilibriumSolver::hold(const std::vector<Hold>& holds, const Vector& displacement) {
  if (holds.empty()) return;
  for (const Hold& h : holds) editor_.hold(h.nodes, h.components, displacement);
  supports_changed();
}

// Without load (no gravity at lambda = 0) the solution is 0 and any finite result passes;
// a NaN from a singular factor must not.
double EquilibriumSolver::relative_residual(const Vector& free_displacement, double lambda) {
  const double load = load_scale(lambda);
  const double residual = max_abs(model_.residual(free_displacement, lambda));
  if (load == 0) return std::isfinite(residual) ? 0 : residual;
  return residual / load;
}

namespace {

std::string ill_conditioned(double lambda, double residual, double tolerance) {
  return "equilibrium at lambda " + std::to_string(lambda) + ": the residual after a fresh " +
         "factorization is " + std::to_string(residual) + " of the load (tolerance " +
         std::to_string(tolerance) + "): the stiffness is too ill-conditioned";
}

}  // namespace

AffinePath EquilibriumSolver::checked_affine_path(double lambda) {
  AffinePath path = affine_path();
  if (relative_residual(path.at(lambda), lambda) <= options_.tolerance) return path;
  factor_current_ = false;
  path = affine_path();
  const double fresh = relative_residual(path.at(lambda), lambda);
  if (fresh > options_.tolerance) throw Error(ill_conditioned(lambda, fresh, options_.tolerance));
  return path;
}

Vector EquilibriumSolver::checked_solve(double lambda) {
  const std::int64_t n = model_.dofs().free_count;
  if (last_solution_valid_ && factor_current_ && lambda == last_lambda_ && n > 0) {
    Vector correction(n);
    if (factor_.solve_sparse(pending_forces_, correction.data())) {
      ++counters_.solves;
      ++counters_.correction_solves;
      Vector u = last_solution_ + correction;
      if (relative_residual(u, lambda) <= options_.tolerance) {
        remember_solution(u, lambda);
        return u;
      }
    }
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!factor_current_) refactorize(Vector::Zero(n), 0.0);
    update_loads();
    Vector u = load0_ + lambda * load1_;
    if (n > 0) factor_.solve(u.data(), n, 1);
    ++counters_.solves;
    const double residual = relative_residual(u, lambda);
    if (residual <= options_.tolerance) {
      remember_solution(u, lambda);
      return u;
    }
    if (attempt == 1) throw Error(ill_conditioned(lambda, residual, options_.tolerance));
    factor_current_ = false;
  }
  return {};
}

// With every dof prescribed (everything held) there is nothing to analyse or solve.
void EquilibriumSolver::supports_changed() {
  last_solution_valid_ = false;  // the free dofs are others now
  stiffness_ = StiffnessMatrix(model_);
  if (model_.dofs().free_count > 0) factor_.analyze(stiffness_);
  reset_kinsol();
  factor_current_ = false;
  find_boundary_bonds();
}

void EquilibriumSolver::find_boundary_bonds() {
  loads_current_ = false;
  boundary_bonds_.clear();
  const int dim = model_.dim();
  auto held = [&](std::int64_t node) {
    for (int c = 0; c < dim; ++c) {
      if (model_.dofs().free_index[node * dim + c] < 0) return true;
    }
    return false;
  };
  for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
    const Bond& bond = model_.lattice.bonds[b];
    if (held(bond.i) || held(bond.j)) boundary_bonds_.push_back(b);
  }
}

AffinePath EquilibriumSolver::affine_path() {
  if (!model_.is_linear()) throw Error("affine_path: the bond law is not linear");
  const std::int64_t n = model_.dofs().free_count;
  if (!factor_current_) refactorize(Vector::Zero(n), 0.0);
  update_loads();
  Eigen::MatrixXd rhs(n, 2);
  rhs.col(0) = load0_;
  rhs.col(1) = load1_;
  if (n > 0) factor_.solve(rhs.data(), n, 2);
  ++counters_.solves;
  return {rhs.col(0), rhs.col(1)};
}

}  // namespace latfrac
