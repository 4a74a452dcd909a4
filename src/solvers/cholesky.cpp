// CHOLMOD-backed sparse Cholesky: analyze once, factorize, solve many right-hand sides.
#include "latfrac/solvers/cholesky.h"

#include <dlfcn.h>
#include <suitesparse/cholmod.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <mutex>
#include <sstream>

#include "backward_solve.h"
#include "latfrac/base/error.h"
#include "latfrac/base/threads.h"

namespace latfrac {

struct CholeskyFactor::State {
  cholmod_common common;
  cholmod_factor* symbolic = nullptr;  // the analysis, kept for fresh supernodal factorizations
  cholmod_factor* factor = nullptr;    // the numeric factor (simplicial LDL' after updates)
  cholmod_dense* solution = nullptr;
  cholmod_dense* work_y = nullptr;
  cholmod_dense* work_e = nullptr;
  // solve_sparse's backward half on threads, for the simplicial factor's pattern (built
  // when first needed after the pattern changed: a factorization, an update that grew it).
  BackwardSolve backward;
  bool backward_stale = true;
  // K's diagonal in the factor's order, from the last fresh factorization and kept up to
  // date by the updates' columns; and the largest value each has had since: the scale
  // against which an updated pivot is judged.
  std::vector<double> diagonal, scale;
};

namespace {

std::string status_text(int status) {
  switch (status) {
    case CHOLMOD_OK:
      return "ok";
    case CHOLMOD_NOT_INSTALLED:
      return "method not installed";
    case CHOLMOD_OUT_OF_MEMORY:
      return "out of memory";
    case CHOLMOD_TOO_LARGE:
      return "integer overflow (problem too large)";
    case CHOLMOD_INVALID:
      return "invalid input";
    case CHOLMOD_GPU_PROBLEM:
      return "GPU problem";
    case CHOLMOD_NOT_POSDEF:
      return "matrix not positive definite";
    case CHOLMOD_DSMALL:
      return "tiny diagonal entry";
  }
  return "status " + std::to_string(status);
}

void check(const cholmod_common& common, bool ok, const char* call) {
  if (ok && common.status == CHOLMOD_OK) return;
  throw Error(std::string(call) + " failed: " + status_text(common.status));
}

// Threads compete on a small machine. OpenBLAS's threads compete with CHOLMOD's
// supernodal kernels: on 2 cores a 3-D factorization takes twice as long with two BLAS
// threads as with one. CHOLMOD's own OpenMP loops (built for 4 threads) cost more than
// they give: on 2 cores a 2-D factorization of 100k nodes took 1.43 s with them and
// 0.98 s without (bench/bench_equilibrium). So both run one thread by default; a user
// who sets OPENBLAS_NUM_THREADS, or OMP_NUM_THREADS or OMP_THREAD_LIMIT, keeps that
// library's setting. Looked up at run time so any BLAS and OpenMP runtime link. OpenMP's
// max-active-levels of 0 runs every parallel region on one thread, even one that asks
// for a number of threads explicitly, as CHOLMOD's do.
void limit_threads() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (!std::getenv("OPENBLAS_NUM_THREADS")) {
      using SetThreads = void (*)(int);
      if (auto set =
              reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
        set(1);
    }
    if (!std::getenv("OMP_NUM_THREADS") && !std::getenv("OMP_THREAD_LIMIT")) {
      using SetLevels = void (*)(int);
      if (auto set =
              reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels")))
        set(0);
    }
  });
}

// A CHOLMOD view of the matrix's arrays (no copy; CHOLMOD never frees it).
cholmod_sparse view_of(StiffnessMatrix& matrix) {
  cholmod_sparse a{};
  a.nrow = a.ncol = static_cast<std::size_t>(matrix.size());
  a.nzmax = static_cast<std::size_t>(matrix.nonzeros());
  a.p = matrix.column_start().data();
  a.i = matrix.row_index().data();
  a.x = matrix.values().data();
  a.stype = 1;
  a.itype = CHOLMOD_LONG;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

// A CHOLMOD view of `columns` dense columns of `rows` doubles stored one after another.
cholmod_dense dense_view(double* x, std::int64_t rows, int columns = 1) {
  cholmod_dense b{};
  b.nrow = b.d = static_cast<std::size_t>(rows);
  b.ncol = static_cast<std::size_t>(columns);
  b.nzmax = b.nrow * b.ncol;
  b.x = x;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  return b;
}

// The simplicial factor's arrays.
SimplicialFactor simplicial(const cholmod_factor& f) {
  return {static_cast<std::int64_t>(f.n), static_cast<const std::int64_t*>(f.p),
          static_cast<const std::int64_t*>(f.nz), static_cast<const std::int64_t*>(f.i),
          static_cast<const double*>(f.x)};
}

}  // namespace

CholeskyFactor::CholeskyFactor(Ordering ordering) : state_(std::make_unique<State>()) {
  limit_threads();
  cholmod_common& c = state_->common;
  if (!cholmod_l_start(&c)) throw Error("cholmod_l_start failed");
  c.print = 0;
  c.error_handler = nullptr;
  c.nmethods = 1;
  c.supernodal = CHOLMOD_SUPERNODAL;
  switch (ordering) {
    case Ordering::metis:
      c.method[0].ordering = CHOLMOD_METIS;
      break;
    case Ordering::nesdis:
      c.method[0].ordering = CHOLMOD_NESDIS;
      break;
    case Ordering::amd:
      c.method[0].ordering = CHOLMOD_AMD;
      break;
  }
  c.postorder = 1;
}

CholeskyFactor::~CholeskyFactor() {
  cholmod_common& c = state_->common;
  cholmod_l_free_factor(&state_->factor, &c);
  cholmod_l_free_factor(&state_->symbolic, &c);
  cholmod_l_free_dense(&state_->solution, &c);
  cholmod_l_free_dense(&state_->work_y, &c);
  cholmod_l_free_dense(&state_->work_e, &c);
  cholmod_l_finish(&c);
}

bool CholeskyFactor::analyzed() const { return state_->symbolic != nullptr; }

void CholeskyFactor::analyze(StiffnessMatrix& matrix, const std::vector<std::int64_t>& given) {
  ++version_;
  cholmod_common& c = state_->common;
  cholmod_l_free_factor(&state_->factor, &c);
  cholmod_l_free_factor(&state_->symbolic, &c);
  inverse_permutation_.clear();
  factorized_ = false;
  state_->backward_stale = true;
  given_ = given;
  cholmod_sparse a = view_of(matrix);
  if (given.empty()) {
    state_->symbolic = cholmod_l_analyze(&a, &c);
    check(c, state_->symbolic != nullptr, "cholmod_l_analyze");
    return;
  }
  if (static_cast<std::int64_t>(given.size()) != matrix.size())
    throw Error("CholeskyFactor::analyze: the given order has the wrong size");
  const int ordering = c.method[0].ordering;
  c.method[0].ordering = CHOLMOD_GIVEN;
  state_->symbolic =
      cholmod_l_analyze_p(&a, const_cast<std::int64_t*>(given.data()), nullptr, 0, &c);
  c.method[0].ordering = ordering;
  check(c, state_->symbolic != nullptr, "cholmod_l_analyze_p");
}

std::vector<std::int64_t> CholeskyFactor::elimination_order() const {
  if (!state_->symbolic) return {};
  const auto* perm = static_cast<const std::int64_t*>(state_->symbolic->Perm);
  return {perm, perm + state_->symbolic->n};
}

void CholeskyFactor::factorize(StiffnessMatrix& matrix) {
  ++version_;
  if (!analyzed()) analyze(matrix);
  cholmod_common& c = state_->common;
  cholmod_sparse a = view_of(matrix);
  factorized_ = false;
  state_->backward_stale = true;
  weakest_ = {};
  // A factor turned simplicial by updates starts again from the supernodal analysis.
  if (!state_->factor || !state_->factor->is_super) {
    cholmod_l_free_factor(&state_->factor, &c);
    state_->factor = cholmod_l_copy_factor(state_->symbolic, &c);
    check(c, state_->factor != nullptr, "cholmod_l_copy_factor");
  }
  const int ok = cholmod_l_factorize(&a, state_->factor, &c);
  if (c.status == CHOLMOD_NOT_POSDEF) {
    const auto* perm = static_cast<const std::int64_t*>(state_->factor->Perm);
    const std::int64_t column = perm[state_->factor->minor];
    std::ostringstream message;
    message << "cholmod_l_factorize: the stiffness matrix is not positive definite (failed at "
               "column "
            << state_->factor->minor << " of " << matrix.size()
            << "): part of the body can move without resistance (a rigid-body motion the face "
               "conditions do not prevent, or a piece cut loose)";
    throw SingularStiffness(message.str(), column);
  }
  check(c, ok, "cholmod_l_factorize");
  // A rigid-body mode can survive roundoff as a tiny positive pivot: catch it here.
  const double rcond = cholmod_l_rcond(state_->factor, &c);
  if (!(rcond > 1e-14)) {
    std::ostringstream message;
    message << "cholmod_l_factorize: the stiffness matrix is singular to working precision "
               "(reciprocal condition estimate "
            << rcond << "): part of the body can move without resistance";
    throw SingularStiffness(message.str(), smallest_pivot_column());
  }
  // The test above compares the smallest pivot with the largest, so a mechanism in a stiff
  // body passes it: at nu = 1/4 (no shear springs) a piece that hangs on one node turns
  // about it with a pivot of 1e-13 of its own diagonal and an rcond of 2e-14 to 1e-10.
  weakest_ = find_weakest_pivot(matrix);
  if (weakest_.position >= 0 && weakest_.ratio < near_mechanism_pivot) {
    const NullMode mode = null_mode(matrix);
    if (weakest_.ratio > mechanism_pivot && !mode.rounding()) {
      factorized_ = true;  // a genuine soft motion
      record_diagonal(matrix);
      return;
    }
    std::ostringstream message;
    message << std::scientific << std::setprecision(2) << "cholmod_l_factorize: a pivot is "
            << weakest_.ratio << " of its diagonal (its motion's energy measured on K: "
            << mode.energy << " of the factor's): part of the body is a mechanism, a "
            << "zero-energy motion of " << mode.moving << " unknowns";
    throw SingularStiffness(message.str(), mode.largest);
  }
  factorized_ = true;
  record_diagonal(matrix);
}

void CholeskyFactor::record_diagonal(StiffnessMatrix& matrix) {
  const auto* perm = static_cast<const std::int64_t*>(state_->factor->Perm);
  const std::int64_t n = static_cast<std::int64_t>(state_->factor->n);
  const std::vector<std::int64_t>& start = matrix.column_start();
  const std::vector<std::int64_t>& row = matrix.row_index();
  const std::vector<double>& value = matrix.values();
  state_->diagonal.assign(n, 0.0);
  for (std::int64_t k = 0; k < n; ++k) {
    const std::int64_t column = perm[k];
    const std::int64_t last = start[column + 1] - 1;
    if (last >= start[column] && row[last] == column) state_->diagonal[k] = value[last];
  }
  state_->scale = state_->diagonal;
}

// One pass over the supernodal factor's diagonal: L(k,k)^2 / K(p,p) with p = Perm[k]. The
// matrix holds its upper triangle with sorted rows, so a column's diagonal is its last entry.
CholeskyFactor::WeakestPivot CholeskyFactor::find_weakest_pivot(StiffnessMatrix& matrix) const {
  const cholmod_factor& f = *state_->factor;
  WeakestPivot weakest;
  if (!f.is_super) return weakest;
  const auto* super = static_cast<const std::int64_t*>(f.super);
  const auto* pi = static_cast<const std::int64_t*>(f.pi);
  const auto* px = static_cast<const std::int64_t*>(f.px);
  const auto* x = static_cast<const double*>(f.x);
  const auto* perm = static_cast<const std::int64_t*>(f.Perm);
  const std::vector<std::int64_t>& start = matrix.column_start();
  const std::vector<std::int64_t>& row = matrix.row_index();
  const std::vector<double>& value = matrix.values();
  for (std::size_t s = 0; s < f.nsuper; ++s) {
    const std::int64_t rows = pi[s + 1] - pi[s];
    for (std::int64_t k = 0; k < super[s + 1] - super[s]; ++k) {
      const double pivot = x[px[s] + k * rows + k];
      const std::int64_t column = perm[super[s] + k];
      const std::int64_t last = start[column + 1] - 1;
      if (last < start[column] || row[last] != column || !(value[last] > 0)) continue;
      const double ratio = pivot * pivot / value[last];
      if (weakest.position < 0 || ratio < weakest.ratio) weakest = {super[s] + k, column, ratio};
    }
  }
  return weakest;
}

// Holding the unknown the motion moves most stops it with the least force: for a piece
// turning about a hinge that is a node far from the hinge, while the pivot's own column
// may lie next to it. The energy x' K x is one pass over the matrix.
CholeskyFactor::NullMode CholeskyFactor::null_mode(StiffnessMatrix& matrix) {
  NullMode mode;
  if (weakest_.position < 0 || !state_->factor || !state_->factor->is_super) return mode;
  cholmod_common& c = state_->common;
  const cholmod_factor& f = *state_->factor;
  const std::int64_t n = static_cast<std::int64_t>(f.n);
  std::vector<double> unit(n, 0.0);
  unit[weakest_.position] = 1.0;
  cholmod_dense b = dense_view(unit.data(), n);
  const int ok = cholmod_l_solve2(CHOLMOD_Lt, state_->factor, &b, nullptr, &state_->solution,
                                  nullptr, &state_->work_y, &state_->work_e, &c);
  check(c, ok, "cholmod_l_solve2");
  const double* y = static_cast<const double*>(state_->solution->x);
  const auto* perm = static_cast<const std::int64_t*>(f.Perm);
  std::vector<double> motion(n);
  double largest = 0;
  for (std::int64_t k = 0; k < n; ++k) {
    motion[perm[k]] = y[k];
    if (std::abs(y[k]) > largest) {
      largest = std::abs(y[k]);
      mode.largest = perm[k];
    }
  }
  for (std::int64_t k = 0; k < n; ++k) mode.moving += std::abs(y[k]) > 1e-3 * largest;
  const std::vector<std::int64_t>& start = matrix.column_start();
  const std::vector<std::int64_t>& row = matrix.row_index();
  const std::vector<double>& value = matrix.values();
  mode.energy = 0;
  for (std::int64_t j = 0; j < n; ++j) {
    for (std::int64_t k = start[j]; k < start[j + 1]; ++k) {
      const std::int64_t i = row[k];
      mode.energy += (i == j ? 1.0 : 2.0) * value[k] * motion[i] * motion[j];
    }
  }
  return mode;
}

void CholeskyFactor::solve(double* rhs, std::int64_t rows, int columns) {
  if (!factorized_) throw Error("CholeskyFactor::solve called before a successful factorization");
  cholmod_common& c = state_->common;
  cholmod_dense b = dense_view(rhs, rows, columns);
  const int ok = cholmod_l_solve2(CHOLMOD_A, state_->factor, &b, nullptr, &state_->solution,
                                  nullptr, &state_->work_y, &state_->work_e, &c);
  check(c, ok, "cholmod_l_solve2");
  const double* x = static_cast<const double*>(state_->solution->x);
  std::copy(x, x + b.nzmax, rhs);
}

void CholeskyFactor::update(const std::vector<Column>& columns, bool downdate) {
  ++version_;
  if (!factorized_) throw Error("CholeskyFactor::update called before a successful factorization");
  if (columns.empty()) return;
  cholmod_common& c = state_->common;
  cholmod_factor* factor = state_->factor;
  if (factor->is_super || factor->is_ll) {
    const int ok = cholmod_l_change_factor(CHOLMOD_REAL, /*to_ll=*/0, /*to_super=*/0,
                                           /*to_packed=*/1, /*to_monotonic=*/1, factor, &c);
    check(c, ok, "cholmod_l_change_factor");
  }
  // C must be permuted like the factor: row r of K is row inverse_perm[r] of C.
  const auto* perm = static_cast<const std::int64_t*>(factor->Perm);
  const std::int64_t n = static_cast<std::int64_t>(factor->n);
  if (static_cast<std::int64_t>(inverse_permutation_.size()) != n) {
    inverse_permutation_.resize(n);
    for (std::int64_t k = 0; k < n; ++k) inverse_permutation_[perm[k]] = k;
  }
  std::size_t entries = 0;
  for (const Column& column : columns) entries += column.size();
  cholmod_sparse* update_matrix = cholmod_l_allocate_sparse(
      n, columns.size(), entries, /*sorted=*/1, /*packed=*/1, 0, CHOLMOD_REAL, &c);
  check(c, update_matrix != nullptr, "cholmod_l_allocate_sparse");
  auto* p = static_cast<std::int64_t*>(update_matrix->p);
  auto* i = static_cast<std::int64_t*>(update_matrix->i);
  auto* x = static_cast<double*>(update_matrix->x);
  std::int64_t k = 0;
  std::vector<std::int64_t> rows;  // in the factor's order: check_paths, check_updated_pivots
  for (std::size_t j = 0; j < columns.size(); ++j) {
    p[j] = k;
    Column sorted;
    for (const auto& [row, value] : columns[j]) {
      sorted.push_back({inverse_permutation_[row], value});
      rows.push_back(inverse_permutation_[row]);
    }
    // K's diagonal changes by +-C(r, j)^2 (for check_updated_pivots).
    if (static_cast<std::int64_t>(state_->diagonal.size()) == n)
      for (const auto& [row, value] : sorted) {
        double& d = state_->diagonal[row];
        d += downdate ? -value * value : value * value;
        state_->scale[row] = std::max(state_->scale[row], d);
      }
    std::sort(sorted.begin(), sorted.end());
    for (const auto& [row, value] : sorted) {
      i[k] = row;
      x[k++] = value;
    }
  }
  p[columns.size()] = k;
  const int ok = cholmod_l_updown(downdate ? 0 : 1, update_matrix, factor, &c);
  const int status = c.status;
  cholmod_l_free_sparse(&update_matrix, &c);
  if (status == CHOLMOD_NOT_POSDEF) {
    factorized_ = false;
    throw Error(
        "cholmod_l_updown: the updated stiffness matrix is not positive definite: part of "
        "the body can move without resistance");
  }
  check(c, ok, "cholmod_l_updown");
  BackwardSolve& backward = state_->backward;
  if (backward.ready() || backward.tree_ready()) {
    backward.check_paths(simplicial(*factor), rows);
    if (!backward.ready() && !backward.tree_ready()) state_->backward_stale = true;
  }
  check_updated_pivots(rows);
}

// A downdate can leave a mechanism that cholmod_l_updown passes: an unknown whose springs
// are all gone but for a contact's, stiff along another axis, keeps a pivot of rounding
// size, of either sign (docs/robustness.md, "Mechanisms"). Such a factor solves with a
// motion of any size that the residual check cannot see (K v ~ 0), and whether the pivot
// comes out negative (refused by updown) or positive (passed) depends on the rounding: the
// ordering, the BLAS. So the pivots D(k) that the update changed (those on the tree's
// paths from its rows, the reach of a forward solve from them), and K's diagonal there,
// are compared with the largest value that diagonal has had since the last fresh
// factorization. At or below mechanism_pivot of it the factor is dropped; the fresh
// factorization that follows judges the stiffness by its own rules and holds a mechanism
// where it finds one.
void CholeskyFactor::check_updated_pivots(const std::vector<std::int64_t>& rows) {
  const cholmod_factor& f = *state_->factor;
  if (state_->diagonal.size() != f.n) return;
  const SimplicialFactor simple = simplicial(f);
  for (const std::int64_t j : reach(rows)) {
    const double floor = mechanism_pivot * state_->scale[j];
    const double pivot = simple.value[simple.start[j]];
    if (pivot > floor && state_->diagonal[j] > floor) continue;
    factorized_ = false;
    throw Error("cholmod_l_updown: a pivot of the updated factor is " +
                std::to_string(pivot / state_->scale[j]) +
                " of its unknown's stiffness: part of the body may move without resistance");
  }
}

namespace {

// The columns of a simplicial factor (column j starts at start[j] with its diagonal and
// lists count[j] rows) that a forward solve from the given rows can change: every column
// reachable along the graph of L, whose edges run from column j to the rows below its
// diagonal. Returned in a depth-first post-order (the caller sorts them). Used where the
// elimination tree does not give the reach (BackwardSolve::tree_ready()).
std::vector<std::int64_t> reached_columns(const std::vector<std::int64_t>& rows,
                                          const std::int64_t* start, const std::int64_t* count,
                                          const std::int64_t* row, std::int64_t n) {
  std::vector<char> reached(n, 0);
  std::vector<std::int64_t> order;
  std::vector<std::pair<std::int64_t, std::int64_t>> stack;  // column, next entry to look at
  for (std::int64_t root : rows) {
    if (reached[root]) continue;
    reached[root] = 1;
    stack.push_back({root, 1});
    while (!stack.empty()) {
      auto& [j, next] = stack.back();
      std::int64_t child = -1;
      while (next < count[j] && child < 0) {
        const std::int64_t i = row[start[j] + next++];
        if (!reached[i]) child = i;
      }
      if (child < 0) {
        order.push_back(j);
        stack.pop_back();
      } else {
        reached[child] = 1;
        stack.push_back({child, 1});
      }
    }
  }
  return order;
}

}  // namespace

// The columns of the simplicial factor that a forward solve from `rows` changes (and an
// update touching them): the union of their tree paths, ascending; from the tree when it
// is current, else along the graph of L.
std::vector<std::int64_t> CholeskyFactor::reach(const std::vector<std::int64_t>& rows) const {
  if (!state_->backward_stale && state_->backward.tree_ready()) return state_->backward.reach(rows);
  const SimplicialFactor simple = simplicial(*state_->factor);
  std::vector<std::int64_t> order =
      reached_columns(rows, simple.start, simple.count, simple.row, simple.n);
  std::sort(order.begin(), order.end());
  return order;
}

bool CholeskyFactor::solve_sparse(const std::vector<Column>& b, double* x) {
  if (!factorized_) throw Error("CholeskyFactor::solve_sparse called before a successful factorization");
  const cholmod_factor& f = *state_->factor;
  const std::int64_t n = static_cast<std::int64_t>(f.n);
  if (f.is_super || f.is_ll || static_cast<std::int64_t>(inverse_permutation_.size()) != n)
    return false;
  if (b.empty()) return true;
  const SimplicialFactor simple = simplicial(f);
  const std::int64_t *start = simple.start, *count = simple.count, *row = simple.row;
  const double* value = simple.value;
  const auto* perm = static_cast<const std::int64_t*>(f.Perm);
  // P b, then L y = P b over the reached columns only (those of all the right-hand sides:
  // one order serves each). In the simplicial LDL' form each column starts with its
  // diagonal (D(j, j)); the entries below it are L(i, j).
  const auto columns = static_cast<std::int64_t>(b.size());
  std::vector<double> y(static_cast<std::size_t>(n * columns), 0.0);
  std::vector<std::int64_t> rows;
  for (std::int64_t c = 0; c < columns; ++c) {
    for (const auto& [r, v] : b[static_cast<std::size_t>(c)]) {
      y[static_cast<std::size_t>(c * n + inverse_permutation_[r])] += v;
      rows.push_back(inverse_permutation_[r]);
    }
  }
  // The reached columns in ascending order, whichever way they are found: the order
  // fixes each y(i)'s sum, so the numbers are the same either way.
  if (state_->backward_stale) {
    state_->backward.build(simple, threads::count());
    state_->backward_stale = false;
  }
  const std::vector<std::int64_t> order = reach(rows);
  for (const std::int64_t j : order)
    if (row[start[j]] != j) return false;
  // Each right-hand side on its own (on the threads, for a factor big enough that the
  // backward half takes them too), over the reached columns of L.
  auto forward_solve = [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t c = first; c < last; ++c) {
      double* yc = y.data() + c * n;
      for (const std::int64_t j : order) {
        const double yj = yc[j];
        if (yj == 0) continue;
        for (std::int64_t k = 1; k < count[j]; ++k) yc[row[start[j] + k]] -= value[start[j] + k] * yj;
      }
    }
  };
  if (state_->backward.ready() && columns > 1)
    threads::for_blocks(columns, 1, forward_solve);
  else
    forward_solve(0, columns);
  // D L' z = y over every column (the solution is dense): over the elimination tree's
  // subtrees on threads (backward_solve.h) where the factor is big enough, else CHOLMOD's
  // own simplicial solve; the same numbers either way. Then x = P' z.
  if (state_->backward.ready()) {
    state_->backward.solve(simple, y.data(), columns);
    for (std::int64_t col = 0; col < columns; ++col)
      for (std::int64_t k = 0; k < n; ++k) x[col * n + perm[k]] = y[col * n + k];
    return true;
  }
  cholmod_common& c = state_->common;
  cholmod_dense forward = dense_view(y.data(), n, static_cast<int>(columns));
  const int ok = cholmod_l_solve2(CHOLMOD_DLt, state_->factor, &forward, nullptr,
                                  &state_->solution, nullptr, &state_->work_y, &state_->work_e, &c);
  check(c, ok, "cholmod_l_solve2");
  const double* z = static_cast<const double*>(state_->solution->x);
  for (std::int64_t col = 0; col < columns; ++col)
    for (std::int64_t k = 0; k < n; ++k) x[col * n + perm[k]] = z[col * n + k];
  return true;
}

// The column (in the matrix's own numbering) of the smallest diagonal entry of the
// supernodal factor: where a nearly free motion shows.
std::int64_t CholeskyFactor::smallest_pivot_column() const {
  const cholmod_factor& f = *state_->factor;
  if (!f.is_super) return -1;
  const auto* super = static_cast<const std::int64_t*>(f.super);
  const auto* pi = static_cast<const std::int64_t*>(f.pi);
  const auto* px = static_cast<const std::int64_t*>(f.px);
  const auto* x = static_cast<const double*>(f.x);
  const auto* perm = static_cast<const std::int64_t*>(f.Perm);
  std::int64_t smallest = -1;
  double value = 0;
  for (std::size_t s = 0; s < f.nsuper; ++s) {
    const std::int64_t rows = pi[s + 1] - pi[s];
    for (std::int64_t k = 0; k < super[s + 1] - super[s]; ++k) {
      const double diagonal = std::abs(x[px[s] + k * rows + k]);
      if (smallest < 0 || diagonal < value) {
        smallest = super[s] + k;
        value = diagonal;
      }
    }
  }
  return smallest < 0 ? -1 : perm[smallest];
}

bool CholeskyFactor::backward_on_threads() const { return state_->backward.ready(); }

std::int64_t CholeskyFactor::factor_nonzeros() const {
  if (!state_->factor) return state_->symbolic ? static_cast<std::int64_t>(state_->common.lnz) : 0;
  const cholmod_factor& f = *state_->factor;
  if (f.is_super) {
    // Count the nonzeros of the supernodal factor from its supernode dimensions.
    const auto* super = static_cast<const std::int64_t*>(f.super);
    const auto* pi = static_cast<const std::int64_t*>(f.pi);
    std::int64_t count = 0;
    for (std::size_t s = 0; s < f.nsuper; ++s) {
      const std::int64_t columns = super[s + 1] - super[s], rows = pi[s + 1] - pi[s];
      count += columns * rows - columns * (columns - 1) / 2;
    }
    return count;
  }
  return static_cast<std::int64_t>(state_->common.lnz);
}

}  // namespace latfrac
