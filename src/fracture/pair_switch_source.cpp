// The next contact switch on an affine path, and taking it.
#include "latfrac/fracture/pair_switch_source.h"

#include "latfrac/base/phase_times.h"

namespace latfrac {

// The first switch after `from`, lowest bond id on ties.
double PairSwitchSource::propose(const AffinePath& path, double from, double to, double) {
  const ScopedPhase phase(Phase::contacts);
  const Model& model = equilibrium_.model();
  proposed_.bond = -1;
  if (!model.has_contact()) return none;
  const double sign = to < from ? -1.0 : 1.0;  // search in s = sign * lambda, increasing
  const double s_from = sign * from, s_to = sign * to;
  const FullPath full = full_path(model, path);
  double first = std::numeric_limits<double>::infinity();
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (!model.contact_capable(b)) continue;
    const PairSwitch change = model.law_of(b)->next_switch(
        model.springs(b), model.state(b), model.bond_displacement(full.at_zero, b),
        sign * model.relative_motion(full.per_lambda, b), s_from, s_to,
        switch_at_start_ && !settling_.held().contains(b));
    if (change.found() && change.s < first) {
      first = change.s;
      proposed_ = {b, change.to, change.direction};
    }
  }
  return proposed_.bond >= 0 ? sign * first : none;
}

void PairSwitchSource::reached(double lambda) {
  if (!settling_.held().empty() && !(std::abs(lambda - unstable_lambda_) <= window(unstable_lambda_)))
    settling_.release();
  std::erase_if(stuck_at_, [&](const auto& entry) {
    return !(std::abs(lambda - entry.second) <= window(entry.second));
  });
  if (lambda == sets_lambda_) return;
  sets_at_lambda_.clear();
  sets_lambda_ = lambda;
  switch_at_start_ = true;
}

void PairSwitchSource::note_sticks() {
  for (const auto& [bond, lambda] : settling_.taken_sticks()) stuck_at_[bond] = lambda;
}

void PairSwitchSource::take(double lambda) {
  note_sticks();
  const PairState from = equilibrium_.model().state(proposed_.bond);
  if (slides(from) && proposed_.state == PairState::closed) {
    stuck_at_[proposed_.bond] = lambda;
  } else if (from == PairState::closed && slides(proposed_.state)) {
    const auto stuck = stuck_at_.find(proposed_.bond);
    if (stuck != stuck_at_.end() && std::abs(lambda - stuck->second) <= window(stuck->second)) {
      settling_.hold(proposed_.bond);
      unstable_lambda_ = lambda;
      settling_.count_cycle();
    }
  }
  equilibrium_.change_pairs({proposed_}, lambda, equilibrium_.displacement(lambda));
  settling_.settle(lambda);
  // No cascade here: a bond that the switch brought to f >= 1 is the break source's next
  // event, at this lambda (its crossing is `from` when f(from) >= 1), and breaks as a
  // cascade would. A switch happens where its force is continuous, so that is rare: none
  // in 9470 switches of the complete scenes, where skipping the search saved 4-12 % of the
  // run (docs/benchmarks.md).
  note_sticks();
  if (!sets_at_lambda_.insert(closed_pairs(equilibrium_.model())).second) {
    switch_at_start_ = false;
    settling_.count_cycle();
  }
}

SwitchGuard PairSwitchSource::guard() const {
  SwitchGuard guard;
  guard.lambda = sets_lambda_;
  guard.switch_at_start = switch_at_start_;
  guard.sets.assign(sets_at_lambda_.begin(), sets_at_lambda_.end());
  for (const auto& [bond, lambda] : stuck_at_) {
    guard.stuck_bonds.push_back(bond);
    guard.stuck_lambdas.push_back(lambda);
  }
  guard.unstable.assign(settling_.held().begin(), settling_.held().end());
  guard.unstable_lambda = unstable_lambda_;
  return guard;
}

void PairSwitchSource::restore(const SwitchGuard& guard) {
  sets_lambda_ = guard.lambda;
  switch_at_start_ = guard.switch_at_start;
  sets_at_lambda_ = {guard.sets.begin(), guard.sets.end()};
  stuck_at_.clear();
  for (std::size_t k = 0; k < guard.stuck_bonds.size() && k < guard.stuck_lambdas.size(); ++k)
    stuck_at_[guard.stuck_bonds[k]] = guard.stuck_lambdas[k];
  settling_.release();
  for (const std::int64_t bond : guard.unstable) settling_.hold(bond);
  unstable_lambda_ = guard.unstable_lambda;
}

}  // namespace latfrac
