// The linear path of the equilibrium solver: the factor, its rank updates when bonds break
// and contacts switch, checked solves and affine paths, and the correction re-solves.
// KINSOL's Newton iteration is in equilibrium_newton.cpp.
#include "latfrac/solvers/equilibrium.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "latfrac/base/error.h"
#include "latfrac/base/phase_times.h"
#include "latfrac/solvers/cholesky.h"
#include "unsymmetric.h"

namespace latfrac {

std::vector<std::int64_t> EquilibriumSolver::anchored_pairs() const {
  std::vector<std::int64_t> pairs;
  if (!model_.has_friction()) return pairs;
  for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
    if (!on_boundary_[b] && model_.contact_capable(b) && model_.law_of(b)->anchored(model_.state(b)))
      pairs.push_back(b);
  }
  return pairs;
}

// With friction, a stick contact off the boundary carries -ks a at zero displacement: its
// anchor is a load like gravity.
void EquilibriumSolver::update_loads() {
  if (loads_current_) return;
  const Vector zero = Vector::Zero(model_.dofs().free_count);
  std::vector<std::int64_t> loaded = boundary_bonds_;
  const std::vector<std::int64_t> anchored = anchored_pairs();  // none without friction
  loaded.insert(loaded.end(), anchored.begin(), anchored.end());
  const Vector at0 = model_.internal_force(model_.full_displacement(zero, 0.0), loaded);
  const Vector at1 = model_.internal_force(model_.full_displacement(zero, 1.0), loaded);
  load0_ = model_.free_part(model_.external_force - at0);
  load1_ = model_.free_part(at0 - at1);
  if (model_.has_prestress()) {
    // Every other pair that carries force carries its prestress at zero displacement, the
    // same at every lambda (no prescribed dof): a load like gravity, which changes when
    // the pair breaks, opens or closes.
    std::vector<std::int64_t> prestressed;
    for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
      if (on_boundary_[b] || model_.state(b) == PairState::open || !model_.law_of(b)) continue;
      if (model_.has_friction() && model_.contact_capable(b) &&
          model_.law_of(b)->anchored(model_.state(b)))
        continue;  // in `loaded` already
      prestressed.push_back(b);
    }
    load0_ -= model_.free_part(model_.internal_force(model_.full_displacement(zero, 0.0), prestressed));
  }
  loads_current_ = true;
}

// A prestressed body's weight and prestress balance (their sum is zero to rounding at
// lambda = 0), so its scale is the larger of the sum and the weight alone.
double EquilibriumSolver::load_scale(double lambda) {
  update_loads();
  const double net = max_abs(load0_ + lambda * load1_);
  if (!model_.has_prestress()) return net;
  return std::max(net, max_abs(model_.free_part(model_.external_force)));
}

void EquilibriumSolver::refactorize(const Vector& free_displacement, double lambda) {
  const ScopedPhase phase(Phase::refactorize);
  if (model_.dofs().free_count == 0) {
    factor_current_ = true;
    return;
  }
  last_solution_valid_ = false;
  lu_current_ = false;  // a fresh factor (a missed residual, say): a fresh LU too
  stiffness_.assemble(model_, model_.full_displacement(free_displacement, lambda));
  factor_->factorize(stiffness_);
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
  h.elimination_order = factor_->given_order();
  h.lu_current = lu_current_ && model_.has_friction();
  if (h.lu_current) {
    h.lu_states = lu_factored_states_;
    h.lu_directions = lu_factored_directions_;
    for (const auto& [bond, change] : lu_changes_) {
      h.lu_change_bonds.push_back(bond);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) h.lu_change_values.push_back(change(r, c));
    }
  }
  const FollowedSolves& f = followed_;
  const std::int64_t n = model_.dofs().free_count;
  if (h.factor_current && f.valid && f.w.rows() == n && f.y.rows() == n &&
      f.factor_version + static_cast<std::uint64_t>(f.pending_updates) == factor_->version() &&
      (!f.bonds.empty() || f.y.cols() == 2)) {
    h.woodbury_bonds = f.bonds;
    for (const std::vector<double>& terms : f.terms) {
      h.woodbury_term_counts.push_back(static_cast<std::int64_t>(terms.size()));
      h.woodbury_terms.insert(h.woodbury_terms.end(), terms.begin(), terms.end());
    }
    h.woodbury_w.assign(f.w.data(), f.w.data() + f.w.size());
    h.woodbury_pending_updates = f.pending_updates;
    h.woodbury_pending_start.push_back(0);
    for (std::size_t c = 0; c < f.pending.size(); ++c) {
      for (const auto& [row, value] : f.pending[c]) {
        h.woodbury_pending_index.push_back(row);
        h.woodbury_pending_value.push_back(value);
      }
      h.woodbury_pending_start.push_back(static_cast<std::int64_t>(h.woodbury_pending_index.size()));
      h.woodbury_pending_sign.push_back(f.pending_sign[c]);
    }
    if (f.y.cols() == 2) {
      h.path_y.assign(f.y.data(), f.y.data() + f.y.size());
      h.path_loads.assign(f.y_load0.data(), f.y_load0.data() + n);
      h.path_loads.insert(h.path_loads.end(), f.y_load1.data(), f.y_load1.data() + n);
    }
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
  const ScopedPhase phase(Phase::setup);
  if (static_cast<std::int64_t>(history.elimination_order.size()) == model_.dofs().free_count &&
      model_.dofs().free_count > 0) {
    analyse(history.elimination_order);
    factor_current_ = false;
  }
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
  if (history.lu_current) rebuild_lu(history);
  if (!history.woodbury_bonds.empty() || !history.path_y.empty()) rebuild_followed(history);
  if (history.solution_valid) {
    last_solution_ = history.solution;
    last_lambda_ = history.solution_lambda;
    last_solution_valid_ = true;
    pending_forces_ = history.pending_forces;
  }
  counters_ = {};
}

// The followed solves as the run had carried them along: W, Y, and the factor updates
// they have not followed yet (the rebuilt factor has had them).
void EquilibriumSolver::rebuild_followed(const History& history) {
  const std::size_t k = history.woodbury_bonds.size();
  const std::int64_t n = model_.dofs().free_count;
  std::size_t values = 0;
  bool one_term_each = true;  // a column of W per coupling term (7 values)
  for (std::int64_t count : history.woodbury_term_counts) {
    values += static_cast<std::size_t>(count);
    one_term_each = one_term_each && count == 7;
  }
  const std::size_t columns = history.woodbury_pending_sign.size();
  if (!one_term_each || history.woodbury_term_counts.size() != k ||
      history.woodbury_terms.size() != values ||
      history.woodbury_w.size() != k * static_cast<std::size_t>(n) ||
      history.woodbury_pending_start.size() != columns + 1 ||
      history.woodbury_pending_index.size() != history.woodbury_pending_value.size() ||
      static_cast<std::size_t>(history.woodbury_pending_start.back()) !=
          history.woodbury_pending_index.size() ||
      history.woodbury_pending_updates < 0 ||
      static_cast<std::uint64_t>(history.woodbury_pending_updates) > factor_->version() ||
      (!history.path_y.empty() && (history.path_y.size() != 2 * static_cast<std::size_t>(n) ||
                                   history.path_loads.size() != history.path_y.size())))
    throw Error("a checkpoint's Woodbury terms or path solve do not fit together");
  for (std::int64_t bond : history.woodbury_bonds)
    if (bond < 0 || bond >= model_.lattice.bond_count())
      throw Error("a checkpoint's Woodbury terms name a bond the lattice does not have");
  FollowedSolves& cache = followed_;
  cache.bonds = history.woodbury_bonds;
  cache.terms.clear();
  std::size_t at = 0;
  for (std::int64_t count : history.woodbury_term_counts) {
    cache.terms.emplace_back(history.woodbury_terms.begin() + static_cast<std::ptrdiff_t>(at),
                             history.woodbury_terms.begin() +
                                 static_cast<std::ptrdiff_t>(at + static_cast<std::size_t>(count)));
    at += static_cast<std::size_t>(count);
  }
  cache.w = Eigen::Map<const Eigen::MatrixXd>(history.woodbury_w.data(), n,
                                              static_cast<Eigen::Index>(k));
  cache.pending.assign(columns, {});
  cache.pending_sign = history.woodbury_pending_sign;
  for (std::size_t c = 0; c < columns; ++c) {
    const std::int64_t first = history.woodbury_pending_start[c];
    const std::int64_t last = history.woodbury_pending_start[c + 1];
    if (first < 0 || last < first) throw Error("a checkpoint's Woodbury columns are out of order");
    for (auto e = static_cast<std::size_t>(first); e < static_cast<std::size_t>(last); ++e) {
      const std::int64_t row = history.woodbury_pending_index[e];
      if (row < 0 || row >= n) throw Error("a checkpoint's Woodbury column leaves the free dofs");
      cache.pending[c].push_back({row, history.woodbury_pending_value[e]});
    }
  }
  if (history.path_y.empty()) {
    cache.y.resize(n, 0);
  } else {
    cache.y = Eigen::Map<const Eigen::MatrixXd>(history.path_y.data(), n, 2);
    cache.y_load0 = Eigen::Map<const Vector>(history.path_loads.data(), n);
    cache.y_load1 = Eigen::Map<const Vector>(history.path_loads.data() + n, n);
  }
  cache.pending_updates = history.woodbury_pending_updates;
  cache.factor_version =
      factor_->version() - static_cast<std::uint64_t>(history.woodbury_pending_updates);
  cache.valid = true;
  finish_woodbury(cache);
}

// The LU as the run had it: factorized with the model in the states and senses of slip
// it was computed for, then the changes since taken back (their columns of W are solved
// again at the next solve, one column at a time as before, so bit for bit).
void EquilibriumSolver::rebuild_lu(const History& history) {
  const std::size_t bonds = model_.pair_states().size();
  if (history.lu_states.size() != bonds || history.lu_directions.size() != 3 * bonds ||
      history.lu_change_values.size() != 9 * history.lu_change_bonds.size())
    throw Error("a checkpoint's LU history does not fit this model");
  const std::vector<PairState> now = model_.pair_states();
  const std::vector<ContactMemory> memory = model_.contact_memory();
  std::vector<std::int64_t> slipping;
  for (std::size_t b = 0; b < bonds; ++b) {
    const auto bond = static_cast<std::int64_t>(b);
    editor_.set_state(bond, static_cast<PairState>(history.lu_states[b]));
    ContactMemory m = memory[b];
    m.slip_direction = Vec3(history.lu_directions[3 * b], history.lu_directions[3 * b + 1],
                            history.lu_directions[3 * b + 2]);
    editor_.set_memory(bond, m);
    if (slides(model_.state(bond)) && model_.contact_capable(bond))
      slipping.push_back(bond);
  }
  factorize_unsymmetric(slipping, model_.dofs().free_count);
  for (std::size_t b = 0; b < bonds; ++b) {
    editor_.set_state(static_cast<std::int64_t>(b), now[b]);
    editor_.set_memory(static_cast<std::int64_t>(b), memory[b]);
  }
  for (std::size_t k = 0; k < history.lu_change_bonds.size(); ++k) {
    Mat3 change;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) change(r, c) = history.lu_change_values[9 * k + 3 * r + c];
    lu_changes_.push_back({history.lu_change_bonds[k], change});
  }
  lu_current_ = true;
}

void EquilibriumSolver::update_factor(std::int64_t bond, const std::vector<RankOneTerm>& terms,
                                      bool downdate) {
  const ScopedPhase phase(Phase::factor_update);
  // Only a bond with a prescribed dof loads the free dofs at zero free displacement.
  if (on_boundary_[bond]) loads_current_ = false;
  if (!factor_current_) return;  // the next factorization assembles the new stiffness
  if (updates_since_factorization_ >= options_.refactor_every) {
    factor_current_ = false;
    last_solution_valid_ = false;
    return;
  }
  std::vector<LinearBackend::Column> columns;
  for (const auto& [weight, direction] : terms) {
    if (weight <= 0) continue;
    LinearBackend::Column column;
    append_on_bond(bond, std::sqrt(weight) * direction, column);
    if (!column.empty()) columns.push_back(std::move(column));
  }
  try {
    factor_->update(columns, downdate);
  } catch (const Error&) {
    factor_current_ = false;  // refactorize; a real singularity is reported there
    last_solution_valid_ = false;
    return;
  }
  ++counters_.factor_updates;
  ++updates_since_factorization_;
  follow_factor_update(columns, downdate);
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
                                       LinearBackend::Column& column) const {
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
  // A frictional contact's anchor and slip force, and a prestressed pair's force at rest,
  // are not in the rank-1 terms that the correction re-solve follows: the next solve is
  // a full one, with fresh loads.
  if ((model_.has_friction() && model_.can_touch(bond)) || model_.has_prestress()) {
    last_solution_valid_ = false;
    loads_current_ = false;
  }
  const Mat3 jacobian_before = lu_current_ ? pair_jacobian(bond) : Mat3::Zero();
  if (factor_current_)
    changes_since_factorization_.push_back({bond, static_cast<std::uint8_t>(state)});
  // The springs in each state: a bond that breaks leaves its direction for its contact's.
  const InteractionLaw* old_law = model_.law_of(bond);
  std::vector<RankOneTerm> removed =
      old_law ? old_law->stiffness_terms(model_.springs(bond), model_.state(bond))
              : std::vector<RankOneTerm>{};
  editor_.set_state(bond, state);
  note_lu_change(bond, jacobian_before);
  const InteractionLaw* new_law = model_.law_of(bond);
  std::vector<RankOneTerm> added =
      new_law ? new_law->stiffness_terms(model_.springs(bond), state) : std::vector<RankOneTerm>{};
  // A term the pair keeps (the normal spring of a bond that breaks into a closed contact)
  // is neither removed nor added: one update instead of two, and no rounding from a
  // downdate and update that cancel.
  for (auto a = added.begin(); a != added.end();) {
    const auto same = std::find_if(removed.begin(), removed.end(), [&](const RankOneTerm& r) {
      return r.weight == a->weight && r.direction == a->direction;
    });
    if (same == removed.end()) {
      ++a;
      continue;
    }
    removed.erase(same);
    a = added.erase(a);
  }
  if (!removed.empty()) update_factor(bond, removed, /*downdate=*/true);
  if (!added.empty()) update_factor(bond, added, /*downdate=*/false);
}

void EquilibriumSolver::set_contact_memory(std::int64_t bond, const ContactMemory& memory) {
  const ContactMemory& old = model_.contact_memory()[bond];
  const InteractionLaw* law = model_.law_of(bond);
  if (law && law->anchored(model_.state(bond)) && old.anchor != memory.anchor) {
    loads_current_ = false;
    last_solution_valid_ = false;
  }
  if (slides(model_.state(bond)) && old.slip_direction != memory.slip_direction) {
    last_solution_valid_ = false;
    const Mat3 before = lu_current_ ? pair_jacobian(bond) : Mat3::Zero();
    editor_.set_memory(bond, memory);
    note_lu_change(bond, before);
    return;
  }
  editor_.set_memory(bond, memory);
}

Mat3 EquilibriumSolver::pair_jacobian(std::int64_t bond) const {
  const InteractionLaw* law = model_.law_of(bond);
  if (!law || model_.state(bond) == PairState::open) return Mat3::Zero();
  return law->jacobian(model_.springs(bond), model_.state(bond), Vec3::Zero());
}

void EquilibriumSolver::note_lu_change(std::int64_t bond, const Mat3& before) {
  if (!lu_current_) return;
  const Mat3 change = pair_jacobian(bond) - before;
  if (!change.isZero(0)) lu_changes_.push_back({bond, change});
}

void EquilibriumSolver::hold(const std::vector<Hold>& holds, const Vector& displacement) {
  if (holds.empty()) return;
  for (const Hold& h : holds) editor_.hold(h.nodes, h.components, displacement);
  supports_changed();
}

// Without load (no gravity at lambda = 0) the solution is 0 and any finite result passes;
// a NaN from a singular factor must not.
double EquilibriumSolver::relative_residual(const Vector& free_displacement, double lambda) {
  const ScopedPhase phase(Phase::residual);
  const double load = load_scale(lambda);
  const double residual = max_abs(model_.residual(free_displacement, lambda));
  if (load == 0) return std::isfinite(residual) ? 0 : residual;
  return residual / load;
}

namespace {

// |K| |u| for the upper triangle of a symmetric matrix in compressed columns.
Vector absolute_product(StiffnessMatrix& matrix, const Vector& u) {
  const std::vector<std::int64_t>& start = matrix.column_start();
  const std::vector<std::int64_t>& row = matrix.row_index();
  const std::vector<double>& value = matrix.values();
  Vector product = Vector::Zero(u.size());
  for (std::int64_t j = 0; j < matrix.size(); ++j) {
    for (std::int64_t k = start[j]; k < start[j + 1]; ++k) {
      const std::int64_t i = row[k];
      product[i] += std::abs(value[k]) * std::abs(u[j]);
      if (i != j) product[j] += std::abs(value[k]) * std::abs(u[i]);
    }
  }
  return product;
}

}  // namespace

// Each bond force starts from a difference u_j - u_i, so a residual cannot drop below
// about eps (|K| |u| + |f|): with displacements of kilometres (a piece hanging on a few
// bonds under strong gravity) that floor can sit above a tight tolerance. Normwise: the
// solve's error spreads over the body.
bool EquilibriumSolver::at_rounding_floor(const Vector& free_displacement, double lambda) {
  constexpr double margin = 16 * std::numeric_limits<double>::epsilon();
  const Vector residual = model_.residual(free_displacement, lambda);
  if (!residual.allFinite()) return false;
  update_loads();
  const Vector floor =
      absolute_product(stiffness_, free_displacement) + (load0_ + lambda * load1_).cwiseAbs();
  return max_abs(residual) <= margin * max_abs(floor);
}

bool EquilibriumSolver::accepted_at_floor(const Vector& free_displacement, double lambda,
                                          double residual) {
  const bool accepted = residual <= max_rounding_excess * options_.tolerance &&
                        at_rounding_floor(free_displacement, lambda);
  if (accepted) ++counters_.floor_acceptances;
  return accepted;
}

// A fresh factorization's solve missed the tolerance (docs/robustness.md). A pivot below
// near_mechanism_pivot of its diagonal is a mechanism that rounding hid from the
// factorization: the unknown it moves most is named, for the singular-stiffness rule to
// hold. Else a residual at the rounding floor, and within max_rounding_excess of the
// tolerance, is accepted. Else the run stops, saying where and what to try.
void EquilibriumSolver::fresh_solve_missed(const Vector& free_displacement, double lambda,
                                           double residual) {
  const LinearBackend::WeakestPivot& weakest = factor_->weakest_pivot();
  if (weakest.position >= 0 && weakest.ratio < CholeskyFactor::near_mechanism_pivot) {
    const LinearBackend::NullMode mode = factor_->null_mode(stiffness_);
    std::ostringstream message;
    message << std::scientific << std::setprecision(2) << "equilibrium at lambda " << lambda
            << ": the residual after a fresh factorization is " << residual
            << " of the load and a pivot is " << weakest.ratio
            << " of its diagonal: a zero-energy motion of " << mode.moving << " unknowns";
    throw SingularStiffness(message.str(), mode.largest);
  }
  if (accepted_at_floor(free_displacement, lambda, residual)) return;
  // With friction, the symmetric factor may be sound while the slipping contacts leave a
  // part (nearly) free to slide: the coupled stiffness is singular to rounding, which an
  // LU need not report. Held like any mechanism (docs/robustness.md).
  if (const std::vector<std::int64_t> slipping = slipping_pairs(); !slipping.empty()) {
    const SlidingMotion sliding = sliding_motion(slipping, model_.dofs().free_count);
    if (sliding.ratio < sliding_mechanism_ratio) {
      std::ostringstream message;
      message << std::scientific << std::setprecision(2) << "equilibrium at lambda " << lambda
              << ": the residual after a fresh factorization is " << residual
              << " of the load and " << slipping.size()
              << " slipping contacts leave a motion of relative stiffness " << sliding.ratio
              << ": a part slides (nearly) freely on them";
      throw SingularStiffness(message.str(), sliding.largest);
    }
  }
  throw Error(ill_conditioned(free_displacement, lambda, residual));
}

// Where: the node of a free unknown, its position and the axis.
std::string EquilibriumSolver::describe_unknown(std::int64_t unknown) const {
  const DofMap& dofs = model_.dofs();
  const int dim = model_.dim();
  const std::vector<int> axes = model_.lattice.axes();
  for (std::int64_t dof = 0; dof < dofs.dof_count(); ++dof) {
    if (dofs.free_index[dof] != unknown) continue;
    const Vec3& x = model_.lattice.positions[dof / dim];
    std::ostringstream text;
    text << std::defaultfloat << std::setprecision(6) << "node " << dof / dim << " (x " << x.x();
    if (dim == 3) text << ", y " << x.y();
    text << ", z " << x.z() << " m) along " << "xyz"[axes[dof % dim]];
    return text.str();
  }
  return "unknown " + std::to_string(unknown);
}

std::string EquilibriumSolver::ill_conditioned(const Vector& free_displacement, double lambda,
                                               double residual) const {
  const Vector r = model_.residual(free_displacement, lambda);
  Eigen::Index worst = 0, moved = 0;
  for (Eigen::Index k = 0; k < r.size(); ++k) {
    if (!(std::abs(r[k]) <= std::abs(r[worst]))) worst = k;
    if (!(std::abs(free_displacement[k]) <= std::abs(free_displacement[moved]))) moved = k;
  }
  std::ostringstream message;
  message << std::scientific << std::setprecision(2) << "equilibrium at lambda " << lambda
          << ": the residual after a fresh factorization is " << residual
          << " of the load (tolerance " << options_.tolerance << ")";
  if (r.size() > 0) {
    message << ", largest at " << describe_unknown(worst) << "; the displacement reaches "
            << std::abs(free_displacement[moved]) << " m at " << describe_unknown(moved);
  }
  const LinearBackend::WeakestPivot& weakest = factor_->weakest_pivot();
  if (weakest.column >= 0) {
    message << "; the weakest pivot is " << weakest.ratio << " of its diagonal, at "
            << describe_unknown(weakest.column);
  }
  if (!std::isfinite(residual)) {
    // No tolerance helps: inf or NaN came out of the solve (the scales overflowed).
    message << ": the solve gave numbers that are not finite; check the scene's scales "
               "(material, strength, gravity and loading values against each other)";
    return message.str();
  }
  // A tolerance near the doubles' precision (1e-15 is allowed) can be below what any solve
  // of the system reaches, with no weak pivot at all: say that, not "ill-conditioned"
  // (Fig. 6 at 1e-15 missed by 1.3e-13 with its weakest pivot at 0.3 of its diagonal).
  if (residual < 1e-10 && weakest.column >= 0 && weakest.ratio > 1e-6) {
    message << ": the solve reached the rounding floor of this system (no pivot is near a "
               "mechanism), which solver.tolerance = "
            << options_.tolerance << " is below; allowed: solver.tolerance of at least "
            << 10 * residual;
    return message.str();
  }
  message << ": the stiffness is too ill-conditioned (part of the body nearly free, or "
             "hanging on a few bonds). Try: ";
  if (!model_.has_contact()) message << "contact.enabled = true; ";
  message << "less breaking (a smaller heterogeneity.spread or gravity.g, a smaller "
             "stepping.increment); solver.tolerance of at least "
          << residual;
  if (std::any_of(model_.shear_stiffness.begin(), model_.shear_stiffness.end(),
                  [](double ks) { return !(ks > 0); }))
    message << "; material.poisson below 0.25 (at 0.25 the shear springs vanish)";
  return message.str();
}

namespace {

// Sets the flag for a scope (on for the retry after a missed residual) and clears it
// after, also when the retry throws.
struct LuRefinement {
  bool& flag;
  LuRefinement(bool& f, bool on) : flag(f) { flag = on; }
  ~LuRefinement() { flag = false; }
  LuRefinement(const LuRefinement&) = delete;
  LuRefinement& operator=(const LuRefinement&) = delete;
};

}  // namespace

AffinePath EquilibriumSolver::checked_affine_path(double lambda) {
  AffinePath path = affine_path();
  if (relative_residual(path.at(lambda), lambda) <= options_.tolerance) return path;
  factor_current_ = false;
  const LuRefinement refine(lu_refinement_, true);
  path = affine_path();
  const double fresh = relative_residual(path.at(lambda), lambda);
  if (fresh > options_.tolerance) fresh_solve_missed(path.at(lambda), lambda, fresh);
  return path;
}

Vector EquilibriumSolver::checked_solve(double lambda) {
  const ScopedPhase phase(Phase::solve);
  const std::int64_t n = model_.dofs().free_count;
  if (last_solution_valid_ && factor_current_ && lambda == last_lambda_ && n > 0) {
    Vector correction(n);
    if (factor_->solve_sparse({pending_forces_}, correction.data())) {
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
    const LuRefinement refine(lu_refinement_, attempt == 1);
    if (!factor_current_) refactorize(Vector::Zero(n), 0.0);
    update_loads();
    Vector u = load0_ + lambda * load1_;
    solve_coupled(u.data(), n, 1);
    const double residual = relative_residual(u, lambda);
    if (residual > options_.tolerance) {
      if (attempt == 0) {
        factor_current_ = false;
        continue;
      }
      fresh_solve_missed(u, lambda, residual);
    }
    remember_solution(u, lambda);
    return u;
  }
  return {};
}

// With every dof prescribed (everything held) there is nothing to analyse or solve.
void EquilibriumSolver::supports_changed() {
  last_solution_valid_ = false;  // the free dofs are others now
  lu_current_ = false;
  unsymmetric_.reset();
  stiffness_ = StiffnessMatrix(model_);
  if (model_.dofs().free_count > 0) analyse(inherited_order());
  reset_kinsol();
  factor_current_ = false;
  find_boundary_bonds();
}

void EquilibriumSolver::analyse(const std::vector<std::int64_t>& given) {
  factor_->analyze(stiffness_, given);
  const auto& free_index = model_.dofs().free_index;
  analysed_globals_.assign(model_.dofs().free_count, 0);
  for (std::size_t g = 0; g < free_index.size(); ++g)
    if (free_index[g] >= 0) analysed_globals_[free_index[g]] = static_cast<std::int64_t>(g);
}

// Holding a part only removes dofs. The filled graph of a principal submatrix eliminated
// in the induced order is a subgraph of the whole matrix's, so the previous fill-reducing
// order, restricted, stays fill-reducing and the ordering (METIS: about a tenth of the 3-D
// reference run with contact, which holds parts 233 times) is not redone.
std::vector<std::int64_t> EquilibriumSolver::inherited_order() const {
  const std::vector<std::int64_t> previous = factor_->elimination_order();
  if (analysed_globals_.empty() || previous.size() != analysed_globals_.size()) return {};
  const auto& free_index = model_.dofs().free_index;
  std::vector<std::int64_t> order;
  order.reserve(model_.dofs().free_count);
  for (std::int64_t k : previous) {
    const std::int64_t f = free_index[analysed_globals_[k]];
    if (f >= 0) order.push_back(f);
  }
  if (static_cast<std::int64_t>(order.size()) != model_.dofs().free_count) return {};
  return order;
}

void EquilibriumSolver::find_boundary_bonds() {
  loads_current_ = false;
  boundary_bonds_.clear();
  on_boundary_.assign(model_.lattice.bond_count(), 0);
  const int dim = model_.dim();
  auto held = [&](std::int64_t node) {
    for (int c = 0; c < dim; ++c) {
      if (model_.dofs().free_index[node * dim + c] < 0) return true;
    }
    return false;
  };
  for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
    const Bond& bond = model_.lattice.bonds[b];
    if (held(bond.i) || held(bond.j)) {
      boundary_bonds_.push_back(b);
      on_boundary_[b] = 1;
    }
  }
}

AffinePath EquilibriumSolver::affine_path() {
  const ScopedPhase phase(Phase::solve);
  if (!model_.is_linear()) throw Error("affine_path: the bond law is not linear");
  const std::int64_t n = model_.dofs().free_count;
  if (!factor_current_) refactorize(Vector::Zero(n), 0.0);
  const std::vector<std::int64_t> slipping = slipping_pairs();
  if (n == 0 || slipping.size() > woodbury_limit) {
    update_loads();
    Eigen::MatrixXd rhs(n, 2);
    rhs.col(0) = load0_;
    rhs.col(1) = load1_;
    solve_coupled(rhs.data(), n, 2);
    return {rhs.col(0), rhs.col(1)};
  }
  // The factor's Y = A^-1 [load0 load1], followed along the updates (FollowedSolves),
  // corrected for the slipping contacts.
  ++counters_.solves;
  const FollowedSolves& followed = followed_solves(slipping, n, true);
  Eigen::MatrixXd x = followed.y;
  if (!slipping.empty()) {
    ++counters_.coupled_solves;
    woodbury_correction(slipping, x.data(), n, 2);
  }
  return {x.col(0), x.col(1)};
}

}  // namespace latfrac
