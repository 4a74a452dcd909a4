// The MPI ranks of a distributed run (include/latfrac/base/parallel.h). Built against MPI
// where latfrac is built with PETSc (LATFRAC_WITH_MPI); without it, one rank.
#include "latfrac/base/parallel.h"

#include <cstdlib>

#ifdef LATFRAC_WITH_MPI
#include <mpi.h>
#endif

namespace latfrac::parallel {

#ifdef LATFRAC_WITH_MPI
namespace {
bool running() {
  int started = 0, finished = 0;
  MPI_Initialized(&started);
  MPI_Finalized(&finished);
  return started && !finished;
}
}  // namespace

int rank() {
  if (!running()) return 0;
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int size() {
  if (!running()) return 1;
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

bool distributed() { return size() > 1; }

double min_over_ranks(double value) {
  if (!distributed()) return value;
  double result = value;
  MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  return result;
}

bool any_rank(bool flag) {
  if (!distributed()) return flag;
  int local = flag ? 1 : 0, result = 0;
  MPI_Allreduce(&local, &result, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return result != 0;
}

std::vector<double> summed(const std::vector<double>& values) {
  if (!distributed()) return values;
  std::vector<double> result(values.size());
  MPI_Allreduce(values.data(), result.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM,
                MPI_COMM_WORLD);
  return result;
}

std::vector<std::int64_t> gathered(const std::vector<std::int64_t>& values) {
  if (!distributed()) return values;
  const int ranks = size();
  int mine = static_cast<int>(values.size());
  std::vector<int> counts(ranks), offsets(ranks, 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<std::int64_t> all(static_cast<std::size_t>(offsets[ranks - 1] + counts[ranks - 1]));
  MPI_Allgatherv(values.data(), mine, MPI_INT64_T, all.data(), counts.data(), offsets.data(),
                 MPI_INT64_T, MPI_COMM_WORLD);
  return all;
}

void abort_all(int status) {
  if (running()) MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}
#else
int rank() { return 0; }
int size() { return 1; }
bool distributed() { return false; }
double min_over_ranks(double value) { return value; }
bool any_rank(bool flag) { return flag; }
std::vector<double> summed(const std::vector<double>& values) { return values; }
std::vector<std::int64_t> gathered(const std::vector<std::int64_t>& values) { return values; }
void abort_all(int status) { std::exit(status); }
#endif

Range share(std::int64_t count) {
  const std::int64_t ranks = size(), r = rank();
  const std::int64_t base = count / ranks, extra = count % ranks;
  Range range;
  range.first = r * base + (r < extra ? r : extra);
  range.last = range.first + base + (r < extra ? 1 : 0);
  return range;
}

}  // namespace latfrac::parallel
