// Breaking one bond, a tied group, and a cascade at one lambda.
#include "latfrac/fracture/breaking.h"

namespace latfrac {

void Breaking::break_bond(std::int64_t bond, const FailureIndex& failure, double lambda,
                          std::int64_t cascade_id) {
  const Model& model = equilibrium_.model();
  const Vector u = equilibrium_.displacement(lambda);
  result_.events.push_back({lambda, bond, failure.value, failure.mode, cascade_id});
  ++breaks_;
  // A bond that breaks in compression becomes a closed contact at once.
  const bool closes = model.can_touch(bond) &&
                      model.lattice.bond_direction[bond].dot(model.bond_displacement(u, bond)) < 0;
  equilibrium_.change_pairs({{bond, closes ? PairState::closed : PairState::open}}, lambda, u);
  settling_.settle(lambda);
  progress_.update(lambda, breaks_);
}

void Breaking::break_group(const std::vector<CriticalBond>& group, double lambda,
                           std::int64_t cascade_id) {
  for (const CriticalBond& member : group) {
    if (equilibrium_.model().intact(member.bond))
      break_bond(member.bond, {member.index, member.mode}, lambda, cascade_id);
  }
}

void Breaking::cascade(double lambda, std::int64_t cascade_id, bool may_stop) {
  for (;;) {
    if (may_break_ && !may_break_(lambda)) return;
    const std::vector<CriticalBond> group =
        evaluator_.critical_group(equilibrium_.model(), equilibrium_.displacement(lambda), 1.0);
    if (group.empty()) return;
    if (cascade_id < 0) cascade_id = new_cascade();
    break_group(group, lambda, cascade_id);
    if (may_stop && between_groups_) between_groups_(lambda, cascade_id);
  }
}

}  // namespace latfrac
