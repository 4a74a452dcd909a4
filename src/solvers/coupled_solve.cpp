// Solves with the stiffness of a model whose contacts slip: the factor of its symmetric
// part, corrected by Sherman-Morrison-Woodbury for a few slipping contacts, or an LU of the
// whole nonsymmetric matrix for many (equilibrium.h, solve_coupled).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include "latfrac/base/error.h"
#include "latfrac/base/phase_times.h"
#include "latfrac/solvers/equilibrium.h"
#include "unsymmetric.h"

namespace latfrac {

std::vector<std::int64_t> EquilibriumSolver::slipping_pairs() const {
  std::vector<std::int64_t> slipping;
  if (model_.has_friction()) {
    for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b)
      if (slides(model_.state(b)) && model_.contact_capable(b)) slipping.push_back(b);
  }
  return slipping;
}

void EquilibriumSolver::solve_coupled(double* rhs, std::int64_t n, int columns) {
  const ScopedPhase phase(Phase::solve);
  ++counters_.solves;
  if (n == 0) return;
  const std::vector<std::int64_t> slipping = slipping_pairs();
  if (slipping.size() > woodbury_limit) {
    followed_.valid = false;
    ++counters_.coupled_solves;
    unsymmetric_solve(slipping, rhs, n, columns);
    return;
  }
  // The right-hand sides are solved on their own, not in one call with W's new columns:
  // CHOLMOD rounds a column differently in a batch of another size, and a resume solves
  // them again alone. (Tried for the path: a resumed run differed from event 65. The
  // event-driven path's solve is now carried along with W instead, and kept in the
  // checkpoint: followed_solves.)
  factor_->solve(rhs, n, columns);
  if (slipping.empty()) return;
  ++counters_.coupled_solves;
  woodbury_correction(slipping, rhs, n, columns);
}

namespace {

// W = A^-1 U and the columns of V for the slipping contacts, and V' x.
struct Coupling {
  const Eigen::MatrixXd& w;
  const std::vector<LinearBackend::Column>& v;
  Eigen::MatrixXd v_times(const Eigen::Ref<const Eigen::MatrixXd>& x) const {
    Eigen::MatrixXd product = Eigen::MatrixXd::Zero(w.cols(), x.cols());
    for (Eigen::Index c = 0; c < w.cols(); ++c)
      for (const auto& [row, value] : v[c]) product.row(c) += value * x.row(row);
    return product;
  }
  Eigen::MatrixXd capacitance() const {
    Eigen::MatrixXd c = v_times(w);
    c.diagonal().array() += 1;
    return c;
  }
};

}  // namespace

namespace {

// The entries where `now` differs from `before` (their difference), with their count.
LinearBackend::Column changed_entries(const Vector& now, const Vector& before) {
  LinearBackend::Column change;
  for (Eigen::Index i = 0; i < now.size(); ++i)
    if (now[i] != before[i]) change.push_back({i, now[i] - before[i]});
  return change;
}

}  // namespace

const EquilibriumSolver::FollowedSolves& EquilibriumSolver::followed_solves(
    const std::vector<std::int64_t>& pairs, std::int64_t n, bool with_path) {
  // W has a column per coupling term: a contact with two terms (3-D's edge of the cone)
  // has two, each with the contact's bond. `slipping` is each column's bond.
  std::vector<std::int64_t> slipping;
  std::vector<std::vector<double>> terms;  // W's key: each column's term, flattened
  for (const std::int64_t bond : pairs) {
    for (const CouplingTerm& t :
         model_.law_of(bond)->coupling_terms(model_.springs(bond), model_.state(bond))) {
      slipping.push_back(bond);
      terms.push_back(
          {t.weight, t.left.x(), t.left.y(), t.left.z(), t.right.x(), t.right.y(), t.right.z()});
    }
  }
  const auto k = static_cast<Eigen::Index>(slipping.size());
  if (with_path) update_loads();
  FollowedSolves& cache = followed_;
  const std::uint64_t version = factor_->version();
  const bool followed =
      cache.valid && cache.w.rows() == n && cache.y.rows() == n &&
      cache.factor_version + static_cast<std::uint64_t>(cache.pending_updates) == version;
  const bool path_kept = followed && cache.y.cols() == 2;
  const bool same_loads = path_kept && cache.y_load0 == load0_ && cache.y_load1 == load1_;
  if (followed && cache.pending.empty() && cache.bonds == slipping && cache.terms == terms &&
      (!with_path || same_loads))
    return cache;
  // A contact that slides as before keeps its column, brought to the factor; the others
  // are solved afresh, in the same solve as the factor updates' columns.
  std::vector<Eigen::Index> kept(slipping.size(), -1), fresh;
  for (std::size_t c = 0; c < slipping.size(); ++c) {
    for (std::size_t j = 0; followed && j < cache.bonds.size() && kept[c] < 0; ++j)
      if (cache.bonds[j] == slipping[c] && cache.terms[j] == terms[c])
        kept[c] = static_cast<Eigen::Index>(j);
    if (kept[c] < 0) fresh.push_back(static_cast<Eigen::Index>(c));
  }
  // The pending updates' columns are solved when W's kept columns need them, or when Y
  // follows. Y follows when that costs no more passes over the factor than solving it
  // afresh: its extra columns are the loads' change (a stick contact's anchor: few
  // entries), and the pending columns when W does not need them anyway. A call without
  // the path keeps Y only where that costs nothing.
  const auto pending = static_cast<Eigen::Index>(followed ? cache.pending.size() : 0);
  const bool w_follows =
      std::any_of(kept.begin(), kept.end(), [](Eigen::Index j) { return j >= 0; });
  LinearBackend::Column change[2];
  // Only a direct factor's solves are exact to rounding: the petsc backend's after
  // updates are iterative, and their tolerance would add up along the updates.
  bool keep_path = path_kept && options_.backend == LinearBackendKind::cholmod;
  if (keep_path && with_path && !same_loads) {
    change[0] = changed_entries(load0_, cache.y_load0);
    change[1] = changed_entries(load1_, cache.y_load1);
    keep_path = static_cast<std::int64_t>(change[0].size() + change[1].size()) <= n / 8;
  }
  if (keep_path) {
    // A solve goes over the factor once per 4 columns (CHOLMOD's simplicial kernels take
    // up to 4 at a time), and Y afresh is one more pass with its two dense columns.
    const Eigen::Index loads = !change[0].empty() + !change[1].empty();
    const auto m = static_cast<Eigen::Index>(fresh.size());
    const Eigen::Index follow = (pending + loads + m + 3) / 4;
    const Eigen::Index afresh = ((w_follows ? pending : 0) + m + 3) / 4 + 1;
    keep_path = with_path ? follow <= afresh : (w_follows || pending == 0) && loads == 0;
  }
  const bool path_afresh = with_path && !keep_path;
  const Eigen::Index r = w_follows || keep_path ? pending : 0;
  // (Moved: the pending list is cleared below.)
  std::vector<LinearBackend::Column> columns(std::make_move_iterator(cache.pending.begin()),
                                             std::make_move_iterator(cache.pending.begin() + r));
  Eigen::Index load_column[2] = {-1, -1};
  for (int c = 0; keep_path && c < 2; ++c) {
    if (change[c].empty()) continue;
    load_column[c] = static_cast<Eigen::Index>(columns.size());
    columns.push_back(std::move(change[c]));
  }
  const auto first_fresh = static_cast<Eigen::Index>(columns.size());
  for (const Eigen::Index c : fresh)
    columns.push_back(coupling_column(slipping[static_cast<std::size_t>(c)],
                                      terms[static_cast<std::size_t>(c)], true));
  // Every column has a few entries (a bond's), so the backend's sparse route solves them
  // (in the factor's forward half only the columns they reach); a backend without one
  // solves them whole.
  // (solve_sparse writes every entry of z, or none when it declines.)
  const auto total = static_cast<Eigen::Index>(columns.size());
  Eigen::MatrixXd z(n, total);
  if (total > 0 && !factor_->solve_sparse(columns, z.data())) {
    z.setZero();
    for (Eigen::Index c = 0; c < total; ++c)
      for (const auto& [row, value] : columns[static_cast<std::size_t>(c)]) z(row, c) += value;
    factor_->solve(z.data(), n, static_cast<int>(total));
  }
  // Brought to the factor: A' = A + C S C' and A X = B give A' (X - A'^-1 C S C' X) = B
  // (nothing to do when no update is pending, r = 0).
  auto bring = [&](Eigen::MatrixXd& x) {
    if (r == 0 || x.cols() == 0) return;
    Eigen::MatrixXd sctx = Eigen::MatrixXd::Zero(r, x.cols());
    for (Eigen::Index c = 0; c < r; ++c)
      for (const auto& [row, value] : columns[static_cast<std::size_t>(c)])
        sctx.row(c) += (cache.pending_sign[static_cast<std::size_t>(c)] * value) * x.row(row);
    x -= z.leftCols(r) * sctx;
  };
  // W keeps its storage and is brought in place when its contacts are the same (each
  // copy of W, n x k, is a pass over memory). Otherwise its kept columns are gathered
  // first and brought together: a product with other columns beside them could round
  // them differently (Eigen's kernels take the last rows and columns apart). Invalid until
  // committed below, so that a throw in between leaves no half-brought W.
  bool same_columns = fresh.empty() && followed && cache.w.cols() == k;
  for (std::size_t c = 0; same_columns && c < slipping.size(); ++c)
    same_columns = kept[c] == static_cast<Eigen::Index>(c);
  cache.valid = false;
  Eigen::MatrixXd w;
  if (same_columns) {
    w = std::move(cache.w);
    bring(w);
  } else {
    std::vector<Eigen::Index> from;
    for (std::size_t c = 0; c < slipping.size(); ++c)
      if (kept[c] >= 0) from.push_back(kept[c]);
    Eigen::MatrixXd moved =
        followed ? Eigen::MatrixXd(cache.w(Eigen::all, from)) : Eigen::MatrixXd(n, 0);
    bring(moved);
    w.resize(n, k);
    Eigen::Index next = 0;
    for (std::size_t c = 0; c < slipping.size(); ++c)
      if (kept[c] >= 0) w.col(static_cast<Eigen::Index>(c)) = moved.col(next++);
    for (std::size_t i = 0; i < fresh.size(); ++i)
      w.col(fresh[i]) = z.col(first_fresh + static_cast<Eigen::Index>(i));
  }
  if (path_afresh) {
    // As the path was always solved: the two loads in one call of the factor's solve.
    cache.y.resize(n, 2);
    cache.y.col(0) = load0_;
    cache.y.col(1) = load1_;
    factor_->solve(cache.y.data(), n, 2);
    cache.y_load0 = load0_;
    cache.y_load1 = load1_;
  } else if (keep_path) {
    bring(cache.y);
    for (int c = 0; c < 2; ++c)
      if (load_column[c] >= 0) cache.y.col(c) += z.col(load_column[c]);
    if (with_path) {
      cache.y_load0 = load0_;
      cache.y_load1 = load1_;
    }
  } else {
    cache.y.resize(n, 0);
  }
  cache.w = std::move(w);
  cache.bonds = slipping;
  cache.terms = std::move(terms);
  cache.factor_version = version;
  cache.pending.clear();
  cache.pending_sign.clear();
  cache.pending_updates = 0;
  cache.valid = true;
  finish_woodbury(cache);
  return cache;
}

// The flattened term is 7 values: the weight w, then a, then b (U gets w a, V b).
LinearBackend::Column EquilibriumSolver::coupling_column(std::int64_t bond,
                                                         const std::vector<double>& term,
                                                         bool left) const {
  if (term.size() != 7) throw Error("a Woodbury column needs one coupling term (7 values)");
  LinearBackend::Column column;
  if (left)
    append_on_bond(bond, term[0] * Vec3(term[1], term[2], term[3]), column);
  else
    append_on_bond(bond, Vec3(term[4], term[5], term[6]), column);
  return column;
}

void EquilibriumSolver::finish_woodbury(FollowedSolves& cache) const {
  cache.v.clear();
  if (cache.bonds.empty()) return;
  for (std::size_t c = 0; c < cache.bonds.size(); ++c)
    cache.v.push_back(coupling_column(cache.bonds[c], cache.terms[c], false));
  cache.capacitance = Coupling{cache.w, cache.v}.capacitance().partialPivLu();
}

void EquilibriumSolver::follow_factor_update(const std::vector<LinearBackend::Column>& columns,
                                             bool downdate) {
  FollowedSolves& cache = followed_;
  if (!cache.valid) return;
  const std::uint64_t before = factor_->version() - 1;
  const auto after = static_cast<Eigen::Index>(cache.pending.size() + columns.size());
  const bool worth = after < cache.w.cols() || (cache.y.cols() == 2 && after <= 4);
  if (cache.factor_version + static_cast<std::uint64_t>(cache.pending_updates) != before ||
      !worth) {
    cache.valid = false;
    return;
  }
  ++cache.pending_updates;
  for (const LinearBackend::Column& column : columns) {
    cache.pending.push_back(column);
    cache.pending_sign.push_back(downdate ? -1.0 : 1.0);
  }
}

void EquilibriumSolver::woodbury_correction(const std::vector<std::int64_t>& slipping,
                                            double* rhs, std::int64_t n, int columns) {
  const FollowedSolves& cache = followed_solves(slipping, n, false);
  const Coupling coupling{cache.w, cache.v};
  Eigen::Map<Eigen::MatrixXd> x(rhs, n, columns);
  x -= coupling.w * cache.capacitance.solve(coupling.v_times(x));
}

// With (I + V' W) y = 0, K (W y) = 0: the motion the slipping contacts leave free. The
// capacitance's smallest singular value against its largest says how free; the motion's
// largest unknown is where to hold it.
EquilibriumSolver::SlidingMotion EquilibriumSolver::sliding_motion(
    const std::vector<std::int64_t>& slipping, std::int64_t n) {
  const FollowedSolves& cache = followed_solves(slipping, n, false);
  const Coupling coupling{cache.w, cache.v};
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(coupling.capacitance(), Eigen::ComputeFullV);
  const Eigen::Index k = cache.w.cols();
  const Vector motion = coupling.w * svd.matrixV().col(k - 1);
  SlidingMotion sliding;
  motion.cwiseAbs().maxCoeff(&sliding.largest);
  const double top = svd.singularValues()(0);
  sliding.ratio = top > 0 ? svd.singularValues()(k - 1) / top : 0.0;
  return sliding;
}

// K = the symmetric stiffness (both triangles, assembled afresh: the factor has been
// updated since the stiffness matrix was last filled) + sum w G'a (G'b)' per slipping
// contact, G the bond's difference operator on the free dofs. Every entry of the
// stiffness pattern is kept (zeros too), and a contact's coupling lies in its bond's
// blocks, so the pattern is that of the supports and its analysis is kept.
void EquilibriumSolver::unsymmetric_solve(const std::vector<std::int64_t>& slipping, double* rhs,
                                          std::int64_t n, int columns) {
  const std::vector<int> axes = model_.lattice.axes();
  if (lu_current_ &&
      static_cast<Eigen::Index>(lu_changes_.size() * axes.size()) > lu_update_limit)
    lu_current_ = false;
  if (!lu_current_) factorize_unsymmetric(slipping, n);
  Unsymmetric& lu = *unsymmetric_;
  lu.lu.umfpackControl()(UMFPACK_IRSTEP) = lu_refinement_ ? 2 : 0;
  // The pairs changed since the factorization: dK = sum over them and the axes c of
  // G'(dJ e_c) (G' e_c)'; W = LU^-1 U is extended by the new columns only.
  if (lu_changes_solved_ < lu_changes_.size()) {
    Eigen::MatrixXd u = Eigen::MatrixXd::Zero(n, 0);
    for (; lu_changes_solved_ < lu_changes_.size(); ++lu_changes_solved_) {
      const auto& [bond, change] = lu_changes_[lu_changes_solved_];
      for (const int axis : axes) {
        LinearBackend::Column left, right;
        append_on_bond(bond, change.col(axis), left);
        append_on_bond(bond, Vec3::Unit(axis), right);
        u.conservativeResize(n, u.cols() + 1);
        u.col(u.cols() - 1).setZero();
        for (const auto& [row, value] : left) u(row, u.cols() - 1) += value;
        lu_v_.push_back(std::move(right));
      }
    }
    const Eigen::MatrixXd solved = lu.lu.solve(u);
    lu_w_.conservativeResize(n, lu_w_.cols() + solved.cols());
    lu_w_.rightCols(solved.cols()) = solved;
  }
  Eigen::Map<Eigen::MatrixXd> x(rhs, n, columns);
  const Eigen::MatrixXd b = x;
  x = lu.lu.solve(b);
  if (lu_w_.cols() == 0) return;
  const Coupling coupling{lu_w_, lu_v_};
  x -= lu_w_ * coupling.capacitance().partialPivLu().solve(coupling.v_times(x));
}


// Factorizes K = A + the slipping contacts' couplings afresh (unsymmetric_solve), and
// records the pair states and senses of slip it was computed for (a checkpoint's
// History replays it).
void EquilibriumSolver::factorize_unsymmetric(const std::vector<std::int64_t>& slipping,
                                              std::int64_t n) {
  const ScopedPhase phase(Phase::refactorize);
  if (!unsymmetric_) unsymmetric_ = std::make_unique<Unsymmetric>();
  Unsymmetric& lu = *unsymmetric_;
  lu_changes_.clear();
  lu_changes_solved_ = 0;
  lu_w_.resize(n, 0);
  lu_v_.clear();
  stiffness_.assemble(model_, model_.full_displacement(Vector::Zero(n), 0.0));
  const std::vector<std::int64_t>& start = stiffness_.column_start();
  const std::vector<std::int64_t>& row = stiffness_.row_index();
  const std::vector<double>& value = stiffness_.values();
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(2 * value.size() + 16 * slipping.size());
  for (std::int64_t j = 0; j < n; ++j) {
    for (std::int64_t k = start[j]; k < start[j + 1]; ++k) {
      entries.emplace_back(static_cast<int>(row[k]), static_cast<int>(j), value[k]);
      if (row[k] != j) entries.emplace_back(static_cast<int>(j), static_cast<int>(row[k]), value[k]);
    }
  }
  for (std::int64_t bond : slipping) {
    for (const CouplingTerm& term :
         model_.law_of(bond)->coupling_terms(model_.springs(bond), model_.state(bond))) {
      LinearBackend::Column left, right;
      append_on_bond(bond, term.weight * term.left, left);
      append_on_bond(bond, term.right, right);
      for (const auto& [r, a] : left)
        for (const auto& [c, b] : right)
          entries.emplace_back(static_cast<int>(r), static_cast<int>(c), a * b);
    }
  }
  const bool analysed = lu.matrix.rows() == n;
  lu.matrix.resize(n, n);
  lu.matrix.setFromTriplets(entries.begin(), entries.end());
  if (!analysed) lu.lu.analyzePattern(lu.matrix);
  lu.lu.factorize(lu.matrix);
  if (lu.lu.info() != Eigen::Success) {
    // Singular: a fresh factor of the symmetric part names a mechanism it has
    // (SingularStiffness); else the slipping contacts made it.
    lu.matrix.resize(0, 0);
    factor_current_ = false;
    refactorize(Vector::Zero(n), 0.0);
    throw SingularStiffness("the stiffness with " + std::to_string(slipping.size()) +
                                " slipping contacts is singular: a part slides freely on them",
                            sliding_motion(slipping, n).largest);
  }
  lu_current_ = true;
    lu_factored_states_.resize(model_.pair_states().size());
  for (std::size_t b = 0; b < lu_factored_states_.size(); ++b)
    lu_factored_states_[b] = static_cast<std::uint8_t>(model_.pair_states()[b]);
  lu_factored_directions_.clear();
  for (const ContactMemory& m : model_.contact_memory())
    lu_factored_directions_.insert(lu_factored_directions_.end(),
                                   {m.slip_direction.x(), m.slip_direction.y(), m.slip_direction.z()});
}

}  // namespace latfrac
