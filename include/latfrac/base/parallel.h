// The MPI ranks of a run with the distributed backend ([solver] backend = "petsc" under
// mpirun, docs/parallel.md). Every rank holds the whole model and takes the same steps;
// the linear algebra is distributed, and so is the search for the next break. Without
// MPI (the cholmod backend, or a build without PETSc) there is one rank, and every call
// here is the identity.
#pragma once

#include <cstdint>
#include <vector>

namespace latfrac::parallel {

// Whether MPI runs (the petsc backend started it) with more than one rank.
bool distributed();
int rank();  // 0 without MPI
int size();  // 1 without MPI

// The smallest value over the ranks.
double min_over_ranks(double value);
// Whether any rank says yes.
bool any_rank(bool flag);
// The sum over the ranks, entry by entry (the same length on every rank).
std::vector<double> summed(const std::vector<double>& values);
// Every rank's values, in rank order, on every rank.
std::vector<std::int64_t> gathered(const std::vector<std::int64_t>& values);
// This rank's share [first, last) of count items, in contiguous blocks in rank order.
struct Range {
  std::int64_t first = 0, last = 0;
};
Range share(std::int64_t count);
// Stops every rank with this status (MPI_Abort): one rank's error must not leave the
// others waiting in a collective call. Returns (exits) only without MPI.
[[noreturn]] void abort_all(int status);

}  // namespace latfrac::parallel
