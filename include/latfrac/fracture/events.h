// The next event on an affine equilibrium path: a bond reaching f = 1, or a contact
// opening or closing, found in closed form (docs/criteria.md, "Crossings").
//
// Along the path u(lambda) = U0 + lambda U1 every bond's relative displacement is affine,
// hence its stresses are too: sigma_n = E/L0 n0.du, the shear stress vector
// G/L0 (du - (n0.du) n0), and (for Drucker-Prager) the mean of its nodes' virial
// stresses. The search runs in s = |lambda| so that compression (lambda < 0) reads like
// extension.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "latfrac/solvers/equilibrium.h"
#include "latfrac/criteria/failure_evaluator.h"

namespace latfrac {

struct PathCrossing {
  double lambda = std::numeric_limits<double>::infinity();  // +inf: none before `to`
  std::int64_t bond = -1;          // the first bond (largest f at lambda, then lowest id)
  std::vector<std::int64_t> tied;  // every bond reaching 1 at lambda within rounding
  bool found() const { return bond >= 0; }
};

// The first bond to reach f = 1 after `from` and no later than `to`. Bonds reaching 1 at
// the same lambda within rounding (1e-12 relative) are tied: the largest f at that lambda
// wins, then the lowest bond id.
PathCrossing next_break(const Model& model, const FailureEvaluator& evaluator,
                        const AffinePath& path, double from, double to);

// The first contact that opens (active, dn rising through 0) or closes (open, dn falling
// through 0) after `from` and no later than `to`; lowest bond id on ties. A contact whose
// dn is already at or past 0 at `from` and still moving the wrong way switches at `from`
// itself: a tie with the switch just made, or roundoff, must not leave it penetrating (or
// pulling) for the rest of the path. `at_from = false` skips those (the caller's guard
// when switches at one lambda cycle).
PathCrossing next_contact_switch(const Model& model, const AffinePath& path, double from,
                                 double to, bool at_from = true);

}  // namespace latfrac
