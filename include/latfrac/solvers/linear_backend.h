// The solver seam: what EquilibriumSolver asks of the linear algebra behind it.
//
// Two backends stand behind it (docs/architecture.md, docs/parallel.md):
// - "cholmod" (CholeskyFactor, cholesky.h): one CHOLMOD factor in this process, updated
//   by rank-1 changes when a bond breaks or a contact switches;
// - "petsc" (petsc_backend.cpp, built where PETSc is found): the stiffness as a PETSc
//   matrix distributed over the MPI ranks, a MUMPS Cholesky factor of it, and conjugate
//   gradients preconditioned with that factor for the stiffness after later changes,
//   since distributed direct solvers have no rank updates.
// Both take the same calls with the same meaning; the matrix and the right-hand sides
// are whole on every rank (the model is replicated), and so is every solution.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "latfrac/mechanics/stiffness.h"
#include "latfrac/solvers/solver_options.h"

namespace latfrac {

class LinearBackend {
 public:
  virtual ~LinearBackend() = default;

  // A sparse column for a rank update: (row, value) pairs in the matrix's own numbering.
  using Column = std::vector<std::pair<std::int64_t, double>>;

  // The pattern: a fill-reducing ordering and a symbolic analysis (CHOLMOD), or the
  // distributed matrix's layout (PETSc). `given`: an elimination order to use (empty:
  // the ordering method's own); a backend that orders by itself ignores it.
  virtual void analyze(StiffnessMatrix& matrix, const std::vector<std::int64_t>& given) = 0;
  // The last analysis's elimination order (empty: none, or the backend keeps none).
  virtual std::vector<std::int64_t> elimination_order() const = 0;
  // The order the last analysis was given (empty: the ordering method chose it).
  virtual const std::vector<std::int64_t>& given_order() const = 0;
  // A fresh factorization of the matrix's values. Throws SingularStiffness (naming the
  // unknown where it showed) when the matrix has a zero-energy motion.
  virtual void factorize(StiffnessMatrix& matrix) = 0;
  // Solves K X = B in place for `columns` right-hand sides stored column after column,
  // with K the factorized matrix and every update since.
  virtual void solve(double* rhs, std::int64_t rows, int columns) = 0;
  // Solves K X = B for right-hand sides with few entries each (rows may repeat: they
  // add), X stored column after column (rows x b.size()), when the backend has a cheaper
  // route for them, writing every entry of X; returns false, leaving X alone, when it
  // has none.
  virtual bool solve_sparse(const std::vector<Column>& b, double* x) = 0;
  // K <- K + C C' (update) or K - C C' (downdate). Throws Error when the backend cannot
  // (the caller then factorizes afresh).
  virtual void update(const std::vector<Column>& columns, bool downdate) = 0;

  // A mechanism shows as a pivot far below its own column's diagonal. The weakest pivot of
  // the last fresh factorization; position -1: none measured (a backend that measures
  // none, or no fresh factorization).
  struct WeakestPivot {
    std::int64_t position = -1;
    std::int64_t column = -1;
    double ratio = 1;
  };
  virtual const WeakestPivot& weakest_pivot() const = 0;
  // The motion at the weakest pivot (cholesky.h says how it is measured); only asked for
  // when weakest_pivot() measured one.
  struct NullMode {
    std::int64_t largest = -1;
    std::int64_t moving = 0;
    double energy = 1;
    bool rounding() const { return !(std::abs(energy - 1) <= 1e-2); }
  };
  virtual NullMode null_mode(StiffnessMatrix& matrix) = 0;

  virtual bool factorized() const = 0;
  // Changes with every analysis, factorization and update: a caller may keep solves with
  // this backend (A^-1 U) while it stays the same.
  virtual std::uint64_t version() const = 0;

  // What the backend did (benchmarks, docs/parallel.md); the cholmod backend counts
  // nothing here (EquilibriumSolver's SolverCounters count its calls).
  struct Statistics {
    long factorizations = 0;  // fresh numeric factorizations, those made inside solve too
    double factor_seconds = 0;
    long iterative_solves = 0;  // CG solves (updates since the factor)
    long iterations = 0;        // CG iterations in all
  };
  virtual const Statistics& statistics() const {
    static const Statistics none;
    return none;
  }
};

// The backend the options name. Throws InputError for "petsc" in a build without PETSc.
std::unique_ptr<LinearBackend> make_linear_backend(const SolverOptions& options);

}  // namespace latfrac

namespace latfrac {

// Whether this build has the petsc backend (CMake found PETSc).
bool petsc_available();
// Starts what the backend needs before a run builds anything: for "petsc", MPI and PETSc
// (once; they are finished when the program exits), so that parallel::rank() is known.
// Throws InputError for "petsc" in a build without PETSc.
void start_linear_backend(const SolverOptions& options);

}  // namespace latfrac
