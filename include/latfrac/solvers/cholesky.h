// Sparse Cholesky factorization of the stiffness matrix with CHOLMOD.
//
// Supernodal LL' with a fill-reducing ordering (METIS by default), 64-bit indices
// (the cholmod_l_* API). The symbolic analysis is done once per pattern and reused by
// every numeric factorization. Every CHOLMOD call is checked; a failure becomes an
// Error naming the call.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "latfrac/solvers/solver_options.h"
#include "latfrac/mechanics/stiffness.h"

namespace latfrac {

class CholeskyFactor {
 public:
  explicit CholeskyFactor(Ordering ordering = Ordering::metis);
  ~CholeskyFactor();
  CholeskyFactor(const CholeskyFactor&) = delete;
  CholeskyFactor& operator=(const CholeskyFactor&) = delete;

  // Fill-reducing ordering and symbolic factorization of the pattern. With `given` (a
  // permutation of 0..n-1, the elimination order) the ordering step is skipped and that
  // order used (CHOLMOD_GIVEN, postordered).
  void analyze(StiffnessMatrix& matrix, const std::vector<std::int64_t>& given = {});
  // The analysis's elimination order (row k of the permuted matrix is row order[k]);
  // empty before an analysis.
  std::vector<std::int64_t> elimination_order() const;
  // Numeric factorization (analyzes first if needed). Throws SingularStiffness, naming the
  // column where it showed, when the matrix is not positive definite or singular to
  // working precision: a rigid-body motion or a part of the body without support.
  void factorize(StiffnessMatrix& matrix);
  // Solves K X = B for `columns` right-hand sides stored column after column, in place.
  void solve(double* rhs, std::int64_t rows, int columns);

  // A sparse column for a rank update: (row, value) pairs in the matrix's own numbering.
  using Column = std::vector<std::pair<std::int64_t, double>>;
  // Solves K x = b for a right-hand side b with few nonzeros (rows may repeat: they add)
  // into x (n entries). Needs the simplicial LDL' factor that updates leave: the forward
  // solve then visits only the columns that b reaches in the factor's elimination graph,
  // about half the work of solve() for the few-entry b of a bond's force. Returns false,
  // leaving x alone, when the factor is still supernodal (use solve()).
  bool solve_sparse(const Column& b, double* x);
  // K <- K + C C' (update) or K - C C' (downdate) on the factor itself, without
  // refactorizing. The first call converts the supernodal LL' factor to the simplicial
  // LDL' form that cholmod_l_updown needs. Throws Error if the result is not positive
  // definite.
  void update(const std::vector<Column>& columns, bool downdate);

  bool analyzed() const;
  bool factorized() const { return factorized_; }
  std::int64_t factor_nonzeros() const;

 private:
  struct State;
  std::int64_t smallest_pivot_column() const;
  std::unique_ptr<State> state_;
  std::vector<std::int64_t> inverse_permutation_;
  bool factorized_ = false;
};

}  // namespace latfrac
