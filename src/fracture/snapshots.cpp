// Recording the lattice and snapshots of the model's state, and the snapshot schedule.
#include "latfrac/fracture/snapshots.h"

#include "latfrac/mechanics/node_stress.h"

namespace latfrac {

void record_lattice(const Model& model, RunResult& result) {
  const Lattice& lattice = model.lattice;
  result.positions.reserve(lattice.node_count() * 3);
  for (const Vec3& p : lattice.positions)
    result.positions.insert(result.positions.end(), {p.x(), p.y(), p.z()});
  result.bonds.reserve(lattice.bond_count() * 2);
  for (const Bond& b : lattice.bonds) {
    result.bonds.insert(result.bonds.end(), {b.i, b.j});
    result.bond_kind.push_back(static_cast<std::int8_t>(b.kind));
  }
}

Snapshot make_snapshot(const Model& model, const Vector& displacement, double lambda,
                       const FailureEvaluator* evaluator) {
  Snapshot s;
  s.lambda = lambda;
  s.displacement.reserve(model.lattice.node_count() * 3);
  for (std::int64_t n = 0; n < model.lattice.node_count(); ++n) {
    const Vec3 u = model.node_displacement(displacement, n);
    s.displacement.insert(s.displacement.end(), {u.x(), u.y(), u.z()});
  }
  s.bond_intact = model.intact_flags();
  if (evaluator) {
    std::vector<BreakMode> modes;
    evaluator->evaluate(model, displacement, s.bond_failure_index, modes);
  } else {
    s.bond_failure_index.assign(model.lattice.bond_count(), 0.0);
  }
  s.node_stress = node_stresses(model, displacement);
  return s;
}

SnapshotSchedule::SnapshotSchedule(const std::vector<double>& requested, double total)
    : lambdas_(requested) {
  if (lambdas_.empty()) lambdas_.push_back(total);
}

}  // namespace latfrac
