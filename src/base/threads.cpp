// Threads for the bond sweeps (include/latfrac/base/threads.h), on OpenMP.
#include "latfrac/base/threads.h"

#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <string>

#include "latfrac/base/error.h"
#include "latfrac/base/parallel.h"

namespace latfrac::threads {
namespace {

int chosen = 0;  // set_count's, 0 when not set

int from_environment() {
  const char* text = std::getenv("LATFRAC_THREADS");
  if (!text || !*text) return 0;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*end != '\0' || value < 1 || value > 4096)
    throw InputError("LATFRAC_THREADS is \"" + std::string(text) +
                     "\": allowed: a whole number from 1 to 4096 (the bond sweeps' threads)");
  return static_cast<int>(value);
}

// CHOLMOD's loops are kept to one thread by OpenMP's max-active-levels of 0
// (solvers/cholesky.cpp), which would keep these sweeps on one thread too: they raise it
// to 1 while they run.
class ActiveLevel {
 public:
  ActiveLevel() : before_(omp_get_max_active_levels()) {
    if (before_ < 1) omp_set_max_active_levels(1);
  }
  ~ActiveLevel() {
    if (before_ < 1) omp_set_max_active_levels(before_);
  }
  ActiveLevel(const ActiveLevel&) = delete;
  ActiveLevel& operator=(const ActiveLevel&) = delete;

 private:
  int before_;
};

}  // namespace

int count() {
  if (chosen > 0) return chosen;
  static const int given = from_environment();
  if (given > 0) return given;
  // Asked each time: MPI starts with the petsc backend, after the first sweeps may have run.
  if (parallel::distributed()) return 1;
  static const int cores = std::max(1, omp_get_num_procs());
  return cores;
}

void set_count(int threads) { chosen = std::max(0, threads); }

int used(std::int64_t items, std::int64_t grain) {
  const std::int64_t most = std::max<std::int64_t>(1, items / std::max<std::int64_t>(grain, 1));
  return static_cast<int>(std::min<std::int64_t>(count(), most));
}

void for_blocks(std::int64_t items, std::int64_t grain,
                const std::function<void(std::int64_t, std::int64_t)>& body) {
  if (items <= 0) return;
  const int threads = used(items, grain);
  if (threads <= 1) {
    body(0, items);
    return;
  }
  // Four blocks per thread, taken in turn by whichever thread is free: the bonds near
  // failure (the costly ones) and the broken ones (skipped) are not spread evenly over
  // the bond ids.
  const std::int64_t blocks = std::min<std::int64_t>(4 * threads, items);
  const ActiveLevel active;
  std::exception_ptr error;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t k = 0; k < blocks; ++k) {
    try {
      body(items * k / blocks, items * (k + 1) / blocks);
    } catch (...) {
#pragma omp critical(latfrac_for_blocks)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace latfrac::threads
