// Sparse Cholesky factorization of the stiffness matrix with CHOLMOD.
//
// Supernodal LL' with a fill-reducing ordering (METIS by default), 64-bit indices
// (the cholmod_l_* API). The symbolic analysis is done once per pattern and reused by
// every numeric factorization. Every CHOLMOD call is checked; a failure becomes an
// Error naming the call.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "latfrac/solvers/linear_backend.h"

namespace latfrac {

class CholeskyFactor final : public LinearBackend {
 public:
  explicit CholeskyFactor(Ordering ordering = Ordering::metis);
  ~CholeskyFactor() override;
  CholeskyFactor(const CholeskyFactor&) = delete;
  CholeskyFactor& operator=(const CholeskyFactor&) = delete;

  // Fill-reducing ordering and symbolic factorization of the pattern. With `given` (a
  // permutation of 0..n-1, the elimination order) the ordering step is skipped and that
  // order used (CHOLMOD_GIVEN, postordered).
  void analyze(StiffnessMatrix& matrix, const std::vector<std::int64_t>& given) override;
  void analyze(StiffnessMatrix& matrix) { analyze(matrix, {}); }
  // The analysis's elimination order (row k of the permuted matrix is row order[k]);
  // empty before an analysis.
  std::vector<std::int64_t> elimination_order() const override;
  // The order the last analysis was given (empty: the ordering method chose it).
  const std::vector<std::int64_t>& given_order() const override { return given_; }
  // Numeric factorization (analyzes first if needed). Throws SingularStiffness, naming the
  // column where it showed, when the matrix is not positive definite or singular to
  // working precision: a rigid-body motion or a part of the body without support; or when
  // a pivot is at most mechanism_pivot of its diagonal, naming the unknown the mechanism
  // moves most.
  void factorize(StiffnessMatrix& matrix) override;
  // Solves K X = B for `columns` right-hand sides stored column after column, in place.
  void solve(double* rhs, std::int64_t rows, int columns) override;

  // Solves K X = B for right-hand sides with few nonzeros each (rows may repeat: they
  // add) into X (n x b.size(), column after column). Needs the simplicial LDL' factor
  // that updates leave: the forward solve then visits only the columns of L that the
  // right-hand sides reach (their elimination tree paths), in ascending order, and the
  // backward solve takes every column at once; about half the work of solve() for a
  // bond's few entries.
  // Returns false, leaving X alone, when the factor is still supernodal (use solve()).
  // On more than one thread (threads::count()) and a factor of at least
  // BackwardSolve::least_entries entries, the backward solve runs over the elimination
  // tree's subtrees in parallel, with CHOLMOD's arithmetic: the same numbers bit for bit
  // (src/solvers/backward_solve.h); the forward half then takes each right-hand side on
  // its own thread (the same numbers too).
  bool solve_sparse(const std::vector<Column>& b, double* x) override;
  // Whether the last solve_sparse took its backward half on threads (for tests, benches).
  bool backward_on_threads() const;
  // K <- K + C C' (update) or K - C C' (downdate) on the factor itself, without
  // refactorizing. The first call converts the supernodal LL' factor to the simplicial
  // LDL' form that cholmod_l_updown needs. Throws Error if the result is not positive
  // definite.
  void update(const std::vector<Column>& columns, bool downdate) override;

  // A mechanism shows as a pivot far below its own column's diagonal of K: L(k,k)^2 is the
  // stiffness of that unknown when the unknowns eliminated before it may move, K(p,p) its
  // stiffness when every other unknown is held. The weakest pivot of the last fresh
  // factorization: its position in the factor's order, its column in the matrix's, and
  // L(k,k)^2 / K(p,p), in [0, 1]. position -1: none measured (no fresh factorization).
  const WeakestPivot& weakest_pivot() const override { return weakest_; }
  // The scan that factorize() makes (O(n)), for benchmarks; needs the fresh supernodal
  // factor of `matrix`.
  WeakestPivot find_weakest_pivot(StiffnessMatrix& matrix) const;
  // At or below mechanism_pivot, factorize() reports a mechanism (SingularStiffness).
  // Below near_mechanism_pivot it reports one when the pivot is rounding: the energy of its
  // motion measured on K disagrees with the factor's. EquilibriumSolver also blames a solve
  // that misses its tolerance on a pivot below near_mechanism_pivot. docs/robustness.md
  // gives the measurements behind both bounds.
  static constexpr double mechanism_pivot = 1e-10;
  static constexpr double near_mechanism_pivot = 1e-6;
  // The motion at the weakest pivot, x = P' L'^-1 e_k: the factor gives it the energy
  // x' K x = e_k' e_k = 1 and K x = P' L e_k, small against x. The unknown it moves most
  // (matrix numbering), how many unknowns move by more than 1e-3 of that, and x' K x
  // measured on the matrix itself. A genuine soft motion has energy 1 to rounding
  // (|1 - energy| ~ eps / ratio, at most 2e-6 in the band); the motion of a rounding pivot
  // has none of its own, and the product shows the factor's error: 0.16 to 3 away from 1
  // where measured. One triangular solve and one pass over K; needs the fresh supernodal
  // factor.
  NullMode null_mode(StiffnessMatrix& matrix) override;

  bool analyzed() const;
  bool factorized() const override { return factorized_; }
  std::int64_t factor_nonzeros() const;

  // Changes with every analysis, factorization and update: a caller may keep solves with
  // this factor (A^-1 U) while it stays the same.
  std::uint64_t version() const override { return version_; }

 private:
  // Keeps K's diagonal (in the factor's order) for update()'s check of its pivots.
  void record_diagonal(StiffnessMatrix& matrix);
  // The simplicial factor's columns that a forward solve from `rows` reaches, ascending.
  std::vector<std::int64_t> reach(const std::vector<std::int64_t>& rows) const;
  // After an update: drops the factor (throws Error) where a pivot it changed fell to a
  // mechanism's (update()'s comment in cholesky.cpp).
  void check_updated_pivots(const std::vector<std::int64_t>& rows);
  std::uint64_t version_ = 0;
  struct State;
  std::int64_t smallest_pivot_column() const;
  WeakestPivot weakest_;
  std::unique_ptr<State> state_;
  std::vector<std::int64_t> inverse_permutation_;
  std::vector<std::int64_t> given_;
  bool factorized_ = false;
};

}  // namespace latfrac
