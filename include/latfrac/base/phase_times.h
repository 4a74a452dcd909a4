// Where a run's wall time goes: the parts of its events (the solves, the factor's updates
// and refactorizations, the node stresses, the criterion's search, the residual checks,
// the contacts' switches, the output) timed on the thread that runs the events.
//
// Each part is a scope (ScopedPhase). Scopes nest: a solve inside a contact switch, a
// refactorization inside a solve. Every second goes to the innermost scope open at the
// time, so the parts add up to the time measured, and a part's seconds include the work
// its scope hands to other threads (the threaded sweeps): they are wall seconds.
#pragma once

#include <array>
#include <functional>
#include <vector>

namespace latfrac {

enum class Phase : int {
  other = 0,      // no part open: the event loop's own bookkeeping
  setup,          // building the lattice and the model, its supports
  solve,          // the solves: paths, W and Y followed, Newton, corrections
  factor_update,  // rank updates of the factor (a break, a contact's switch)
  refactorize,    // numeric factorizations afresh
  node_stress,    // the node stresses (the virial sweeps)
  criterion,      // the criterion: crossings, screens, ranks, tied groups
  residual,       // the residual checks of the solves
  contacts,       // the contacts' switches: proposals, settling, commits
  output,         // snapshots and checkpoints (the final result file is written later)
};
constexpr int phase_count = 10;
// A name for the summary: "solves", "factor updates", ...
const char* to_string(Phase phase);

// The seconds spent in each phase, from a clock given in seconds.
class PhaseClock {
 public:
  using Now = std::function<double()>;
  PhaseClock();  // the steady clock
  explicit PhaseClock(Now now);
  // Opens a phase inside the one open now; leave() closes the innermost.
  void enter(Phase phase);
  void leave();
  // Every phase's seconds since reset(), the open ones counted up to now.
  std::array<double, phase_count> seconds() const;
  // Zero for every phase, and nothing open: the time from now on goes to `other`. Call it
  // with no scope open (a scope open then loses its time, and its leave() does nothing).
  void reset();

 private:
  Now now_;
  std::vector<Phase> open_;
  double since_ = 0;
  std::array<double, phase_count> seconds_{};
};

// The calling thread's clock (the run's events run on one thread).
PhaseClock& phase_clock();

// Times a scope as `phase` on the calling thread's clock.
class ScopedPhase {
 public:
  explicit ScopedPhase(Phase phase) : clock_(phase_clock()) { clock_.enter(phase); }
  ~ScopedPhase() { clock_.leave(); }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  PhaseClock& clock_;
};

}  // namespace latfrac
