// The two linear backends on a real run (issue 20, docs/parallel.md): the event-driven
// run of a problem file, stopped after a number of events, with solver.backend "cholmod"
// or "petsc" (under mpirun for more than one rank). Prints one table row: the setup (the
// model, the first factorization and the first event), the time per event after it, the
// factorizations and their mean time, the CG solves and iterations (petsc), and the peak
// resident memory of each rank.
//
//   build/bench/bench_backend cholmod 1000 10
//   build/bench/bench_backend petsc 1000 10
//   mpirun --allow-run-as-root -np 2 -x OPENBLAS_NUM_THREADS=1 build/bench/bench_backend petsc 1000 10
//   build/bench/bench_backend petsc 700 10 problems/reference-3d.toml
//
// Arguments: backend, lattice spacing (m), events, problem file (default
// problems/reference-3d.toml, run event-driven), contact (default false: every event is
// then a break). Built only with the petsc backend.
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "latfrac/base/parallel.h"
#include "latfrac/fracture/run_control.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/scene/run.h"
#include "latfrac/solvers/linear_backend.h"

#include "peak_memory.h"

using namespace latfrac;

namespace {

using Clock = std::chrono::steady_clock;

// Stops the run after `events` calls between events, and notes when the first and the
// last of them came. Every rank counts alike, so every rank stops at the same event.
class StopAfter : public RunControl {
 public:
  explicit StopAfter(long events) : events_(events) {}
  bool stop_requested() const override {
    const auto now = Clock::now();
    if (calls_ == 0) first_ = now;
    last_ = now;
    return ++calls_ >= events_;
  }
  bool checkpoint_due() override { return false; }
  void save(RunResult&, RunCheckpoint&) override {}
  long calls() const { return calls_; }
  Clock::time_point first() const { return first_; }
  Clock::time_point last() const { return last_; }

 private:
  long events_;
  mutable long calls_ = 0;
  mutable Clock::time_point first_, last_;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string backend = argc > 1 ? argv[1] : "petsc";
  const std::string spacing = argc > 2 ? argv[2] : "2000";
  const long events = argc > 3 ? std::stol(argv[3]) : 10;
  const std::string problem = argc > 4 ? argv[4] : "problems/reference-3d.toml";
  // Without contact by default: every event is then a break (with contact, most of the
  // first events are contacts closing).
  const std::string contact = argc > 5 ? argv[5] : "false";
  try {
    const auto start = Clock::now();
    const Scene scene = read_problem_file(
        problem, {"lattice.spacing=" + spacing, "stepping.method=event",
                  "solver.backend=" + backend, "contact.enabled=" + contact});
    start_linear_backend(scene.solver);
    StopAfter control(events);
    RunOptions options;
    options.progress = false;
    options.control = &control;
    LinearBackend::Statistics backend_statistics;
    options.backend_statistics = &backend_statistics;
    const RunResult result = run_scene(scene, options);
    const double setup = std::chrono::duration<double>(control.first() - start).count();
    const double per_event = control.calls() > 1
                                 ? std::chrono::duration<double>(control.last() - control.first())
                                           .count() /
                                       static_cast<double>(control.calls() - 1)
                                 : 0;
    std::vector<double> peaks(parallel::size(), 0.0);
    double mine = peak_mib();
    if (parallel::distributed()) {
      MPI_Gather(&mine, 1, MPI_DOUBLE, peaks.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    } else {
      peaks[0] = mine;
    }
    if (parallel::rank() != 0) return 0;
    std::string peak_list;
    for (double p : peaks) {
      if (!peak_list.empty()) peak_list += ' ';
      peak_list += std::to_string(static_cast<long>(p));
    }
    const RunSummary& s = result.summary;
    const LinearBackend::Statistics& b = backend_statistics;
    std::printf(
        "| backend | ranks | spacing m | dofs | events | breaks | setup s | s per event | "
        "solves | factorizations | s per factorization | CG solves | CG iterations | peak MiB "
        "per rank |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    const bool petsc = backend == "petsc";
    std::printf("| %s | %d | %s | %zu | %ld | %ld | %.1f | %.3f | %ld | %ld | %s | %s | %s | %s |\n",
                backend.c_str(), parallel::size(), spacing.c_str(), 3 * result.node_count(),
                control.calls(), static_cast<long>(s.breaks), setup, per_event,
                static_cast<long>(s.solves),
                petsc ? b.factorizations : static_cast<long>(s.factorizations),
                petsc && b.factorizations
                    ? std::to_string(b.factor_seconds / static_cast<double>(b.factorizations)).c_str()
                    : "-",
                petsc ? std::to_string(b.iterative_solves).c_str() : "-",
                petsc ? std::to_string(b.iterations).c_str() : "-", peak_list.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_backend: %s\n", e.what());
    parallel::abort_all(1);
  }
}
