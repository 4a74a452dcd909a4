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

namespace {

// The search over `bonds` (all of this rank's share when null). Only crossings up to
// `needed_until` (in lambda) and to the earliest found, with room for ties, are needed:
// a bond that cannot cross by then is skipped.
PathCrossing search(const Model& model, const FailureEvaluator& evaluator,
                    const PathStresses& stresses, double from, double to, double needed_until,
                    const std::vector<std::int64_t>* bonds) {
  const ScopedPhase phase(Phase::criterion);
  const double sign = to < from ? -1.0 : 1.0;  // search in s = sign * lambda, increasing
  const double s_from = sign * from, s_to = sign * to;
  const double s_needed =
      std::isnan(needed_until) ? std::numeric_limits<double>::infinity() : sign * needed_until;
  const parallel::Range mine = bonds ? parallel::Range{0, static_cast<std::int64_t>(bonds->size())}
                                     : parallel::share(model.lattice.bond_count());
  const auto bond_at = [&](std::int64_t k) { return bonds ? (*bonds)[k] : k; };
  std::vector<double> crossing(mine.last - mine.first, std::numeric_limits<double>::infinity());
  // Each thread's block keeps its own earliest crossing; a bond skipped there cannot cross
  // before it (nor, then, in the tie window of the earliest of all), so the event is the
  // same on any number of threads.
  threads::for_blocks(mine.last - mine.first, threads::bond_grain, [&](std::int64_t begin, std::int64_t end) {
    double block_first = std::numeric_limits<double>::infinity();
    for (std::int64_t k = mine.first + begin; k < mine.first + end; ++k) {
      const std::int64_t b = bond_at(k);
      if (!model.intact(b)) continue;
      // Only a crossing up to the earliest found so far (with room for ties) can matter.
      const double earliest = std::min(block_first, s_needed);
      const double needed = std::isfinite(earliest)
                                ? earliest + 2 * FailureEvaluator::tie_tolerance *
                                                 std::max(std::abs(earliest), 1e-300)
                                : std::numeric_limits<double>::infinity();
      double& c = crossing[k - mine.first];
      c = evaluator.first_crossing(model, b, stresses, s_from, s_to, needed);
      block_first = std::min(block_first, c);
    }
  });
  double first = std::numeric_limits<double>::infinity();
  for (const double c : crossing) first = std::min(first, c);
  if (!bonds) first = parallel::min_over_ranks(first);
  PathCrossing event;
  if (!std::isfinite(first)) return event;
  const double window = first + FailureEvaluator::tie_tolerance * std::max(std::abs(first), 1e-300);
  for (std::int64_t k = mine.first; k < mine.last; ++k) {
    if (crossing[k - mine.first] <= window) event.tied.push_back(bond_at(k));
  }
  if (!bonds) event.tied = parallel::gathered(event.tied);
  event.lambda = sign * first;
  return event;
}

}  // namespace

PathCrossing next_break(const Model& model, const FailureEvaluator& evaluator,
                        const PathStresses& stresses, double from, double to, double needed_until) {
  return search(model, evaluator, stresses, from, to, needed_until, nullptr);
}

PathCrossing next_break_among(const Model& model, const FailureEvaluator& evaluator,
                              const PathStresses& stresses, const std::vector<std::int64_t>& bonds,
                              double from, double to, double needed_until) {
  return search(model, evaluator, stresses, from, to, needed_until, &bonds);
}

double BreakSource::propose(const AffinePath& path, double from, double to, double needed_until) {
  const bool current = stresses_ && equilibrium_.path_at_hand() && &path == &equilibrium_.path(from);
  if (!current) {
    proposed_ = next_break(equilibrium_.model(), evaluator_, path, from, to);
    return proposed_.lambda;
  }
  const double sign = to < from ? -1.0 : 1.0;
  if (!screen_) {
    proposed_ = next_break(equilibrium_.model(), evaluator_, stresses_->current(from, sign), from,
                           to, needed_until);
    return proposed_.lambda;
  }
  // A path whose stresses are not at hand is screened first; the full search's stresses
  // become the screen's reference.
  const FullPath full = full_path(equilibrium_.model(), path);
  if (!stresses_->holds_current(sign)) {
    std::optional<PathCrossing> screened =
        screen_->next_break(full, from, to, needed_until, breaking_.breaks());
    if (screened) {
      proposed_ = std::move(*screened);
      return proposed_.lambda;
    }
  }
  const PathStresses& stresses = stresses_->current(from, sign);
  screen_->set_reference(full, stresses, sign, breaking_.breaks());
  proposed_ = next_break(equilibrium_.model(), evaluator_, stresses, from, to, needed_until);
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
