// Breaking one bond, a tied group, and a cascade at one lambda.
#include "latfrac/fracture/breaking.h"

#include "latfrac/criteria/crack_plane.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/mechanics/node_stress.h"

namespace latfrac {

void Breaking::break_bond(std::int64_t bond, const FailureIndex& failure, double lambda,
                          std::int64_t cascade_id) {
  const Model& model = equilibrium_.model();
  const Vector u = equilibrium_.displacement(lambda);
  result_.events.push_back({lambda, bond, failure.value, failure.mode, cascade_id});
  ++breaks_;
  // With contacts along cracks, the crack's plane from the stress the bond failed under
  // (the criterion's reading: the mean of its two nodes' stresses).
  if (model.contacts_along_cracks() && model.can_touch(bond)) {
    const Bond& pair = model.lattice.bonds[bond];
    const VoigtStress stress =
        bond_stress_tensor(node_stresses_at(model, u, {pair.i, pair.j}), pair);
    equilibrium_.set_contact_normal(
        bond, crack_plane_normal(stress, model.lattice.bond_direction[bond], failure.mode,
                                 model.crack_friction_angle, model.dim()));
  }
  // A bond that breaks in compression becomes a closed contact at once.
  const bool closes = model.can_touch(bond) &&
                      model.contact_direction(bond).dot(model.bond_displacement(u, bond)) < 0;
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
