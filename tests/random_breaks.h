// Test and benchmark helper: break random bonds one by one, as a cascade would, keeping
// the body held.
#pragma once

#include <cstdint>
#include <random>

#include "latfrac/solvers/equilibrium.h"
#include "latfrac/mechanics/fragments.h"

namespace latfrac::testing {

// Picks `count` random intact bonds (a fixed `seed`) whose loss cuts no part loose and
// calls apply(bond), which must break it: these callers are about the factor, not about
// fragments.
template <class Apply>
void for_random_supported_breaks(Model& model, int count, std::uint64_t seed, Apply apply) {
  const FragmentDetector fragments(model);
  ModelEditor trial(model);
  std::mt19937_64 random(seed);
  std::uniform_int_distribution<std::int64_t> pick(0, model.lattice.bond_count() - 1);
  for (int broken = 0; broken < count;) {
    const std::int64_t bond = pick(random);
    if (!model.intact(bond)) continue;
    trial.set_state(bond, PairState::open);
    const bool cuts_loose = !fragments.unsupported_after_break(model, bond).empty();
    trial.set_state(bond, PairState::intact);
    if (cuts_loose) continue;
    apply(bond);
    ++broken;
  }
}

// Breaks them through the solver, which downdates its factor after each.
inline void break_random_bonds(Model& model, EquilibriumSolver& solver, int count,
                               std::uint64_t seed) {
  for_random_supported_breaks(model, count, seed, [&](std::int64_t bond) {
    solver.set_pair_state(bond, PairState::open);
  });
}

}  // namespace latfrac::testing
