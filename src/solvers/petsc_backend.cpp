// The petsc backend (linear_backend.h, docs/parallel.md): the stiffness as a PETSc matrix
// whose rows are split over the MPI ranks in contiguous blocks, a MUMPS factorization of
// it, and, since a distributed factor cannot be updated by rank-1 changes, conjugate
// gradients on the changed stiffness K_r = K0 +- C C' preconditioned with K0's factor.
// The preconditioned operator is the identity plus a term of rank at most the number of
// update columns, so CG needs few iterations (docs/parallel.md measures 3 after one break,
// 16 after a hundred at 1000 m). Every solve is checked by EquilibriumSolver as with
// CHOLMOD. When the CG iterations since the factorization have cost more than a fresh
// factorization would have, the backend factorizes the changed stiffness afresh.
//
// The matrix, the right-hand sides and the solutions are whole on every rank (the model
// is replicated): each rank hands PETSc its rows, and each solution is gathered to all.
#include "petsc_backend.h"

#include "latfrac/base/error.h"

#ifdef LATFRAC_WITH_PETSC
#include <petscksp.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "latfrac/base/parallel.h"
#include "latfrac/solvers/cholesky.h"
#endif

namespace latfrac {

#ifndef LATFRAC_WITH_PETSC

bool petsc_available() { return false; }

void start_linear_backend(const SolverOptions& options) {
  if (options.backend == LinearBackendKind::petsc) make_petsc_backend();
}

std::unique_ptr<LinearBackend> make_petsc_backend() {
  throw InputError(
      "solver.backend = \"petsc\": this latfrac was built without PETSc (install "
      "libpetsc-real-dev, as scripts/install-deps.sh does, and build again)");
}

#else

namespace {

void check(PetscErrorCode code, const char* what) {
  if (code != 0)
    throw Error(std::string("petsc backend: ") + what + " failed (PETSc error " +
                std::to_string(static_cast<int>(code)) + ")");
}

void finish_petsc() {
  PetscBool started = PETSC_FALSE;
  PetscInitialized(&started);
  if (started) PetscFinalize();
}

void start_petsc() {
  PetscBool started = PETSC_FALSE;
  PetscInitialized(&started);
  if (started) return;
  check(PetscInitializeNoArguments(), "PetscInitialize");
  // Errors come back as codes, which become latfrac Errors; PETSc prints nothing.
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  std::atexit(finish_petsc);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class PetscBackend final : public LinearBackend {
 public:
  PetscBackend() { start_petsc(); }
  ~PetscBackend() override { destroy(); }
  PetscBackend(const PetscBackend&) = delete;
  PetscBackend& operator=(const PetscBackend&) = delete;

  void analyze(StiffnessMatrix& matrix, const std::vector<std::int64_t>& given) override;
  std::vector<std::int64_t> elimination_order() const override {
    return locator_.elimination_order();
  }
  const std::vector<std::int64_t>& given_order() const override { return locator_.given_order(); }
  void factorize(StiffnessMatrix& matrix) override;
  void solve(double* rhs, std::int64_t rows, int columns) override;
  bool solve_sparse(const std::vector<Column>&, double*) override { return false; }
  void update(const std::vector<Column>& columns, bool downdate) override;
  const WeakestPivot& weakest_pivot() const override { return none_; }
  NullMode null_mode(StiffnessMatrix&) override { return {}; }
  bool factorized() const override { return factorized_; }
  std::uint64_t version() const override { return version_; }
  const Statistics& statistics() const override { return statistics_; }

 private:
  void destroy();
  // Copies k_ into k0_ and factorizes it with MUMPS (its analysis kept from the first
  // time); prices the factorization in solves for the refactorization rule.
  void factorize_current();
  void locate_mechanism(StiffnessMatrix& matrix, const std::string& what);
  // factorize_current() inside a solve; false: the stiffness has a mechanism now.
  bool refactorize_in_solve();

  std::int64_t n_ = 0;
  PetscInt first_ = 0, last_ = 0;  // this rank's rows
  // This rank's rows of the full symmetric pattern: columns and the slot of each entry
  // in the StiffnessMatrix's upper-triangle values.
  std::vector<PetscInt> row_start_, row_columns_;
  std::vector<std::int64_t> row_slots_;
  Mat k_ = nullptr;   // the stiffness now: the factorized one with every update since
  Mat k0_ = nullptr;  // the factorized one
  KSP direct_ = nullptr;  // MUMPS Cholesky of k0_
  KSP cg_ = nullptr;      // CG on k_, preconditioned with direct_
  Vec b_ = nullptr, x_ = nullptr, all_ = nullptr;
  VecScatter to_all_ = nullptr;
  bool updated_ = false;  // k_ differs from k0_
  bool factorized_ = false;
  std::uint64_t version_ = 0;
  // CHOLMOD's analysis of the same pattern, in the order the cholmod backend would use:
  // where MUMPS finds a mechanism, this factorization names the same unknown as the
  // cholmod backend does (locate_mechanism). Its numeric factor exists only then.
  CholeskyFactor locator_;
  WeakestPivot none_;
  // The refactorization rule: a fresh factorization costs `factor_in_solves_` solves with
  // the factor (from MUMPS's operation counts at the last one, the same on every rank);
  // CG iterations since then are counted against it.
  double factor_in_solves_ = 0;
  Statistics statistics_;
  PetscInt extra_workspace_ = 35;  // MUMPS's ICNTL(14): percent over its workspace estimate
  long iterations_since_factor_ = 0;
};

PetscErrorCode apply_factor(PC pc, Vec x, Vec y) {
  void* context = nullptr;
  PetscErrorCode code = PCShellGetContext(pc, &context);
  if (code) return code;
  return KSPSolve(static_cast<KSP>(context), x, y);
}

void PetscBackend::destroy() {
  KSPDestroy(&cg_);
  KSPDestroy(&direct_);
  MatDestroy(&k0_);
  MatDestroy(&k_);
  VecScatterDestroy(&to_all_);
  VecDestroy(&all_);
  VecDestroy(&b_);
  VecDestroy(&x_);
  factorized_ = false;
  updated_ = false;
}

void PetscBackend::analyze(StiffnessMatrix& matrix, const std::vector<std::int64_t>& given) {
  destroy();
  locator_.analyze(matrix, given);

  ++version_;
  n_ = matrix.size();
  if (n_ > std::numeric_limits<PetscInt>::max())
    throw Error("petsc backend: " + std::to_string(n_) +
                " unknowns exceed this PETSc's 32-bit indices");
  const parallel::Range mine = parallel::share(n_);
  first_ = static_cast<PetscInt>(mine.first);
  last_ = static_cast<PetscInt>(mine.last);
  const PetscInt local = last_ - first_;
  // The full pattern of this rank's rows from the upper triangle (both halves), with
  // every entry of the pattern, zero or not: updates then stay inside it.
  const auto& start = matrix.column_start();
  const auto& row = matrix.row_index();
  std::vector<std::vector<std::pair<PetscInt, std::int64_t>>> rows(local);
  for (std::int64_t j = 0; j < n_; ++j) {
    for (std::int64_t p = start[j]; p < start[j + 1]; ++p) {
      const std::int64_t r = row[p];
      if (r >= first_ && r < last_) rows[r - first_].push_back({static_cast<PetscInt>(j), p});
      if (r != j && j >= first_ && j < last_)
        rows[j - first_].push_back({static_cast<PetscInt>(r), p});
    }
  }
  row_start_.assign(1, 0);
  row_columns_.clear();
  row_slots_.clear();
  std::vector<PetscInt> diagonal(local, 0), off(local, 0);
  for (PetscInt i = 0; i < local; ++i) {
    std::sort(rows[i].begin(), rows[i].end());
    for (const auto& [c, slot] : rows[i]) {
      row_columns_.push_back(c);
      row_slots_.push_back(slot);
      ++((c >= first_ && c < last_) ? diagonal : off)[i];
    }
    row_start_.push_back(static_cast<PetscInt>(row_columns_.size()));
  }
  const auto n = static_cast<PetscInt>(n_);
  check(MatCreate(PETSC_COMM_WORLD, &k_), "MatCreate");
  check(MatSetSizes(k_, local, local, n, n), "MatSetSizes");
  check(MatSetType(k_, MATAIJ), "MatSetType");
  check(MatSeqAIJSetPreallocation(k_, 0, diagonal.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(k_, 0, diagonal.data(), 0, off.data()),
        "MatMPIAIJSetPreallocation");
  std::vector<double> zeros;
  for (PetscInt i = 0; i < local; ++i) {
    const PetscInt global = first_ + i, count = row_start_[i + 1] - row_start_[i];
    zeros.assign(count, 0.0);
    check(MatSetValues(k_, 1, &global, count, &row_columns_[row_start_[i]], zeros.data(),
                       INSERT_VALUES),
          "MatSetValues");
  }
  check(MatAssemblyBegin(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  check(MatSetOption(k_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(k_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(k_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
  check(MatCreateVecs(k_, &x_, &b_), "MatCreateVecs");
  check(VecScatterCreateToAll(x_, &to_all_, &all_), "VecScatterCreateToAll");
}

// A zero-energy motion stops MUMPS (a null pivot, or a failed factorization). The cholmod
// backend's factorization names the unknown where it shows; it is asked here, on the
// same matrix (every rank holds it whole) in the same elimination order, so that the run
// holds the same unknown as with the cholmod backend. Only then does this rank hold a
// CHOLMOD factor.
void PetscBackend::locate_mechanism(StiffnessMatrix& matrix, const std::string& what) {
  // Either way the numeric factor is freed again (a fresh analysis in its own order).
  const auto release = [&] { locator_.analyze(matrix, locator_.elimination_order()); };
  try {
    locator_.factorize(matrix);  // throws SingularStiffness naming the unknown
  } catch (const SingularStiffness&) {
    release();
    throw;
  }
  release();
  throw Error("petsc backend: " + what + ", where CHOLMOD finds no zero-energy motion");
}

// A fresh factorization inside a solve (the cost rule, or CG that did not converge). A
// mechanism that the updates made shows here; the solve then answers NaN, the caller's
// residual check fails, and the caller factorizes its freshly assembled stiffness, where
// factorize() names the unknown, as with the cholmod backend (whose update fails there).
bool PetscBackend::refactorize_in_solve() {
  try {
    factorize_current();
    return true;
  } catch (const SingularStiffness&) {
    return false;
  }
}

void PetscBackend::factorize_current() {
  factorized_ = false;
  // k0_ keeps its pattern (k_'s, every bond's): MUMPS's analysis is made once, and a later
  // factorization is numeric only.
  if (!k0_)
    check(MatDuplicate(k_, MAT_COPY_VALUES, &k0_), "MatDuplicate");
  else
    check(MatCopy(k_, k0_, SAME_NONZERO_PATTERN), "MatCopy");
  const auto start = std::chrono::steady_clock::now();
  // MUMPS estimates its workspace in the analysis; when the factorization needs more
  // (INFOG(1) -8, -9, -11: pivoting and fill beyond the estimate), it is redone with the
  // estimate raised (ICNTL(14), percent), doubled each time.
  for (int attempt = 0;; ++attempt) {
    PC pc;
    if (!direct_) {
      check(KSPCreate(PETSC_COMM_WORLD, &direct_), "KSPCreate");
      check(KSPSetType(direct_, KSPPREONLY), "KSPSetType");
      check(KSPGetPC(direct_, &pc), "KSPGetPC");
      check(PCSetType(pc, PCCHOLESKY), "PCSetType");
      check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
      check(KSPSetOperators(direct_, k0_, k0_), "KSPSetOperators");
      check(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType");
      Mat f;
      check(PCFactorGetMatrix(pc, &f), "PCFactorGetMatrix");
      // Null-pivot detection (ICNTL(24)): a pivot below CNTL(3) times the matrix's norm
      // is a zero-energy motion, counted in INFOG(28).
      check(MatMumpsSetIcntl(f, 24, 1), "MatMumpsSetIcntl(24)");
      check(MatMumpsSetCntl(f, 3, 1e-12), "MatMumpsSetCntl(3)");
      check(MatMumpsSetIcntl(f, 14, extra_workspace_), "MatMumpsSetIcntl(14)");
    } else {
      check(KSPSetOperators(direct_, k0_, k0_), "KSPSetOperators");
      check(KSPGetPC(direct_, &pc), "KSPGetPC");
    }
    const PetscErrorCode code = KSPSetUp(direct_);
    Mat f;
    check(PCFactorGetMatrix(pc, &f), "PCFactorGetMatrix");
    PetscInt info = 0, null_pivots = 0;
    MatMumpsGetInfog(f, 1, &info);
    MatMumpsGetInfog(f, 28, &null_pivots);
    if (code == 0 && info >= 0 && null_pivots == 0) break;
    KSPDestroy(&direct_);  // the next factorization starts from a fresh analysis
    if ((info == -8 || info == -9 || info == -11) && attempt < 8) {
      extra_workspace_ *= 2;
      continue;
    }
    if (null_pivots > 0 || info == -10)
      throw SingularStiffness("MUMPS found the stiffness singular (" +
                                  std::to_string(null_pivots) + " null pivots, INFOG(1) " +
                                  std::to_string(info) + ")",
                              -1);
    throw Error("petsc backend: the MUMPS factorization failed (INFOG(1) " +
                std::to_string(info) + ", PETSc error " + std::to_string(static_cast<int>(code)) +
                ")");
  }
  statistics_.factorizations += 1;
  statistics_.factor_seconds += seconds_since(start);
  // The price of a factorization in solves with it: MUMPS's operation counts (RINFOG(3),
  // the elimination's flops, over 4 flops per factor entry INFOG(29) for the forward and
  // backward solve). Counts, not a clock, so that a run decides alike every time and on
  // every rank.
  {
    Mat f;
    PC pc;
    check(KSPGetPC(direct_, &pc), "KSPGetPC");
    check(PCFactorGetMatrix(pc, &f), "PCFactorGetMatrix");
    PetscReal flops = 0;
    PetscInt entries = 0;
    MatMumpsGetRinfog(f, 3, &flops);
    MatMumpsGetInfog(f, 29, &entries);
    // MUMPS gives a count past 2^31 negative, in millions.
    const double factor_entries =
        entries >= 0 ? static_cast<double>(entries) : -1e6 * static_cast<double>(entries);
    factor_in_solves_ = factor_entries > 0 ? flops / (4.0 * factor_entries) : 1.0;
  }
  iterations_since_factor_ = 0;

  PC shell;
  if (!cg_) {
    check(KSPCreate(PETSC_COMM_WORLD, &cg_), "KSPCreate");
    check(KSPSetOperators(cg_, k_, k_), "KSPSetOperators");
    check(KSPSetType(cg_, KSPCG), "KSPSetType");
    // The true residual: |b - K x| <= 1e-13 |b| (EquilibriumSolver checks the result).
    check(KSPSetNormType(cg_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    check(KSPSetTolerances(cg_, 1e-13, 1e-300, PETSC_DEFAULT, 1000), "KSPSetTolerances");
    check(KSPGetPC(cg_, &shell), "KSPGetPC");
    check(PCSetType(shell, PCSHELL), "PCSetType");
    check(PCShellSetApply(shell, apply_factor), "PCShellSetApply");
  }
  check(KSPGetPC(cg_, &shell), "KSPGetPC");
  check(PCShellSetContext(shell, direct_), "PCShellSetContext");
  updated_ = false;
  factorized_ = true;
  ++version_;
}

void PetscBackend::factorize(StiffnessMatrix& matrix) {
  if (!k_ || matrix.size() != n_) analyze(matrix, locator_.given_order());
  const std::vector<double>& values = matrix.values();
  std::vector<double> row_values;
  for (PetscInt i = 0; i + first_ < last_; ++i) {
    const PetscInt global = first_ + i, count = row_start_[i + 1] - row_start_[i];
    row_values.resize(count);
    for (PetscInt k = 0; k < count; ++k) row_values[k] = values[row_slots_[row_start_[i] + k]];
    check(MatSetValues(k_, 1, &global, count, &row_columns_[row_start_[i]], row_values.data(),
                       INSERT_VALUES),
          "MatSetValues");
  }
  check(MatAssemblyBegin(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  try {
    factorize_current();
  } catch (const SingularStiffness& singular) {
    locate_mechanism(matrix, singular.what());
  }
}

void PetscBackend::update(const std::vector<Column>& columns, bool downdate) {
  if (!k_) throw Error("petsc backend: update before an analysis");
  const double sign = downdate ? -1.0 : 1.0;
  for (const Column& column : columns) {
    for (const auto& [r, vr] : column) {
      if (r < first_ || r >= last_) continue;
      const auto row = static_cast<PetscInt>(r);
      for (const auto& [c, vc] : column) {
        const auto col = static_cast<PetscInt>(c);
        check(MatSetValue(k_, row, col, sign * vr * vc, ADD_VALUES), "MatSetValue");
      }
    }
  }
  check(MatAssemblyBegin(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(k_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  updated_ = true;
  ++version_;
}

void PetscBackend::solve(double* rhs, std::int64_t rows, int columns) {
  if (rows != n_)
    throw Error("petsc backend: a solve of " + std::to_string(rows) + " rows with a matrix of " +
                std::to_string(n_));
  const auto answer_nan = [&] {
    std::fill(rhs, rhs + rows * columns, std::numeric_limits<double>::quiet_NaN());
  };
  if (!factorized_) return answer_nan();
  // Refactorize when the CG iterations since the last factorization, each a solve with
  // the factor, have cost more than a fresh factorization.
  if (updated_ && iterations_since_factor_ > factor_in_solves_ && !refactorize_in_solve())
    return answer_nan();
  for (int c = 0; c < columns; ++c) {
    double* column = rhs + static_cast<std::int64_t>(c) * rows;
    double* local = nullptr;
    check(VecGetArray(b_, &local), "VecGetArray");
    std::copy(column + first_, column + last_, local);
    check(VecRestoreArray(b_, &local), "VecRestoreArray");
    if (!updated_) {
      check(KSPSolve(direct_, b_, x_), "KSPSolve (MUMPS)");
    } else {
      ++statistics_.iterative_solves;
      check(KSPSolve(cg_, b_, x_), "KSPSolve (CG)");
      KSPConvergedReason reason;
      PetscInt iterations = 0;
      check(KSPGetConvergedReason(cg_, &reason), "KSPGetConvergedReason");
      check(KSPGetIterationNumber(cg_, &iterations), "KSPGetIterationNumber");
      iterations_since_factor_ += iterations;
      statistics_.iterations += iterations;
      if (reason < 0) {
        // CG did not converge: the changes took K0's factor too far from K, or made a
        // mechanism. A fresh factorization of K solves it directly, or finds the mechanism.
        if (!refactorize_in_solve()) return answer_nan();
        check(KSPSolve(direct_, b_, x_), "KSPSolve (MUMPS)");
      }
    }
    check(VecScatterBegin(to_all_, x_, all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(to_all_, x_, all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const double* gathered = nullptr;
    check(VecGetArrayRead(all_, &gathered), "VecGetArrayRead");
    std::copy(gathered, gathered + rows, column);
    check(VecRestoreArrayRead(all_, &gathered), "VecRestoreArrayRead");
  }
}

}  // namespace

bool petsc_available() { return true; }

void start_linear_backend(const SolverOptions& options) {
  if (options.backend == LinearBackendKind::petsc) start_petsc();
}

std::unique_ptr<LinearBackend> make_petsc_backend() { return std::make_unique<PetscBackend>(); }

#endif

}  // namespace latfrac
