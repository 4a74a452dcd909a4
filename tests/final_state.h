// Test helper: the model of a finished run rebuilt in its final state, to check it
// independently of the run (residuals, reactions, contact forces).
#pragma once

#include "latfrac/mechanics/model.h"
#include "latfrac/fracture/run_result.h"
#include "latfrac/scene/model_builder.h"

namespace latfrac::testing {

// A fresh model of the scene with the last snapshot's intact bonds, its displacement on
// every dof, and contacts closed where the displacement presses them (dn < 0).
struct FinalState {
  Model model;
  Vector displacement;
  double lambda = 0;
};

inline FinalState final_state(const Scene& scene, const RunResult& result) {
  FinalState state{build_model(scene), {}, 0};
  const Snapshot& last = result.snapshots.back();
  state.lambda = last.lambda;
  ModelEditor editor(state.model);
  for (std::int64_t b = 0; b < state.model.lattice.bond_count(); ++b)
    editor.set_state(b, last.bond_intact[b] ? PairState::intact : PairState::open);
  const int dim = state.model.dim();
  const std::vector<int> axes = state.model.lattice.axes();
  state.displacement.resize(state.model.dofs().dof_count());
  for (std::int64_t n = 0; n < state.model.lattice.node_count(); ++n) {
    for (int c = 0; c < dim; ++c)
      state.displacement[n * dim + c] = last.displacement[3 * n + axes[c]];
  }
  for (std::int64_t b = 0; b < state.model.lattice.bond_count(); ++b) {
    const double dn = state.model.lattice.bond_direction[b].dot(
        state.model.bond_displacement(state.displacement, b));
    if (state.model.contact_capable(b) && dn < 0) editor.set_state(b, PairState::closed);
  }
  return state;
}

}  // namespace latfrac::testing
