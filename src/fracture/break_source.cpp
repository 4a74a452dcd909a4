// The next break on an affine path, and taking it.
#include "latfrac/fracture/break_source.h"

#include <cmath>

#include "latfrac/base/parallel.h"
#include "latfrac/base/phase_times.h"
#include "latfrac/base/threads.h"

namespace latfrac {

FullPath full_path(const Model& model, const AffinePath& path) {
  FullPath full;
  full.at_zero = model.full_displacement(path.gravity, 0.0);
  full.per_lambda = model.full_displacement(path.at(1.0), 1.0) - full.at_zero;
  return full;
}

// With the petsc backend under MPI, each rank searches its own block of bonds; the
// earliest crossing is the minimum over the ranks, and the tied group (every bond within
// the tie window of it) is gathered in bond order: the same event on any number of ranks.
PathCrossing next_break(const Model& model, const FailureEvaluator& evaluator,
                        const AffinePath& path, double from, double to) {
  const double sign = to < from ? -1.0 : 1.0;
  const FullPath full = full_path(model, path);
  return next_break(model, evaluator,
                    evaluator.path_stresses(model, full.at_zero, full.per_lambda, sign), from, to);
}

const PathStresses& PathStressCache::current(double lambda, double sign) {
  if (!valid_ || version_ != equilibrium_.path_version() || sign_ != sign) {
    const Model& model = equilibrium_.model();
    const FullPath full = full_path(model, equilibrium_.path(lambda));
    stresses_ = evaluator_.path_stresses(model, full.at_zero, full.per_lambda, sign);
    valid_ = true;
    version_ = equilibrium_.path_version();
    sign_ = sign;
  }
  return stresses_;
}

PathCrossing next_break(const Model& model, const FailureEvaluator& evaluator,
                        const PathStresses& stresses, double from, double to) {
  const ScopedPhase phase(Phase::criterion);
  const double sign = to < from ? -1.0 : 1.0;  // search in s = sign * lambda, increasing
  const double s_from = sign * from, s_to = sign * to;
  const parallel::Range mine = parallel::share(model.lattice.bond_count());
  std::vector<double> crossing(mine.last - mine.first, std::numeric_limits<double>::infinity());
  // Each thread's block keeps its own earliest crossing; a bond skipped there cannot cross
  // before it (nor, then, in the tie window of the earliest of all), so the event is the
  // same on any number of threads.
  threads::for_blocks(mine.last - mine.first, threads::bond_grain, [&](std::int64_t begin, std::int64_t end) {
    double block_first = std::numeric_limits<double>::infinity();
    for (std::int64_t b = mine.first + begin; b < mine.first + end; ++b) {
      if (!model.intact(b)) continue;
      // Only a crossing up to the earliest found so far (with room for ties) can matter.
      const double needed_until =
          std::isfinite(block_first)
              ? block_first +
                    2 * FailureEvaluator::tie_tolerance * std::max(std::abs(block_first), 1e-300)
              : std::numeric_limits<double>::infinity();
      double& c = crossing[b - mine.first];
      c = evaluator.first_crossing(model, b, stresses, s_from, s_to, needed_until);
      block_first = std::min(block_first, c);
    }
  });
  double first = std::numeric_limits<double>::infinity();
  for (const double c : crossing) first = std::min(first, c);
  first = parallel::min_over_ranks(first);
  PathCrossing event;
  if (!std::isfinite(first)) return event;
  const double window = first + FailureEvaluator::tie_tolerance * std::max(std::abs(first), 1e-300);
  for (std::int64_t b = mine.first; b < mine.last; ++b) {
    if (crossing[b - mine.first] <= window) event.tied.push_back(b);
  }
  event.tied = parallel::gathered(event.tied);
  event.lambda = sign * first;
  return event;
}

double BreakSource::propose(const AffinePath& path, double from, double to) {
  const bool current = stresses_ && equilibrium_.path_at_hand() && &path == &equilibrium_.path(from);
  proposed_ = current ? next_break(equilibrium_.model(), evaluator_,
                                   stresses_->current(from, to < from ? -1.0 : 1.0), from, to)
                      : next_break(equilibrium_.model(), evaluator_, path, from, to);
  return proposed_.lambda;
}

// Every bond that reached f = 1 at this lambda, within rounding, breaks now (explicitly:
// roundoff may leave its f a hair below 1).
void BreakSource::take(double lambda) {
  const std::int64_t cascade_id = breaking_.new_cascade();
  const std::vector<CriticalBond> group =
      evaluator_.indices_of(equilibrium_.model(), equilibrium_.displacement(lambda), proposed_.tied);
  breaking_.break_group(group, lambda, cascade_id);
  breaking_.cascade(lambda, cascade_id, true);
}

}  // namespace latfrac
