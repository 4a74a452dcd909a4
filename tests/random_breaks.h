// Test helper: break random bonds one by one, as a cascade would, keeping the body held.
#pragma once

#include <cstdint>
#include <random>

#include "latfrac/equilibrium.h"
#include "latfrac/fragments.h"

namespace latfrac::testing {

// Breaks `count` random intact bonds (a fixed `seed`), skipping any whose loss would cut a
// part loose, and downdates the solver's factor after each: these tests are about the
// factor, not about fragments.
inline void break_random_bonds(Model& model, EquilibriumSolver& solver, int count,
                               std::uint64_t seed) {
  const FragmentDetector fragments(model);
  std::mt19937_64 random(seed);
  std::uniform_int_distribution<std::int64_t> pick(0, model.lattice.bond_count() - 1);
  for (int broken = 0; broken < count;) {
    const std::int64_t bond = pick(random);
    if (!model.intact[bond]) continue;
    model.intact[bond] = 0;
    if (!fragments.unsupported_after_break(model, bond).empty()) {
      model.intact[bond] = 1;
      continue;
    }
    solver.remove_bond(bond);
    ++broken;
  }
}

}  // namespace latfrac::testing
