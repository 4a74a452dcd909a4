// Static equilibrium by over-relaxed nodal Gauss-Seidel: the classical baseline solver.
//
// A sweep visits the nodes in index order. At a node with free degrees of freedom it
// takes the out-of-balance force F (external minus internal, from the node's own bonds:
// intact bonds through the bond law, active contact springs as kn n0 n0') and the nodal
// stiffness block B (the sum of the bonds' tangent blocks, restricted to the free
// components), and moves the node by omega B^-1 F. This is the block form of the
// spec's "omega sum F / sum k"; when B is singular the node falls back to that scalar
// form, omega F_c / B_cc per free component (B_cc is the sum of the bonds' stiffness
// along c). omega = 1 is plain Gauss-Seidel; 1 < omega < 2 over-relaxes.
//
// The stopping test is the direct solver's (equilibrium.h): max |R| over the free dofs
// relative to max |R(0, lambda)|, checked before the first sweep, every check_interval
// sweeps and after the last one. The solver is kept so that the convergence study can
// show what the method the paper's model used costs; EquilibriumSolver is the one to use.
#pragma once

#include <cstdint>
#include <vector>

#include "latfrac/mechanics/model.h"
#include "latfrac/solvers/solver_options.h"

namespace latfrac {

struct RelaxationReport {
  long sweeps = 0;
  double relative_residual = 0;  // max |R| / max |R(0, lambda)| at the end
  bool converged = false;        // relative_residual <= options.relaxation_tolerance
};

class RelaxationSolver {
 public:
  // Sweeps between two checks of the global residual (a check costs about one sweep).
  static constexpr long check_interval = 10;

  // Throws InputError unless 0 < relaxation_omega < 2, relaxation_tolerance > 0 and
  // relaxation_max_sweeps >= 0. Each node's bonds come from Model::node_bonds().
  explicit RelaxationSolver(const SolverOptions& options);

  // Over-relaxed nodal Gauss-Seidel from the given free displacement (updated in place)
  // at extension strain lambda, until the relative residual <= relaxation_tolerance or
  // relaxation_max_sweeps sweeps. Never throws for non-convergence: the report says so.
  // A zero load (max |R(0, lambda)| = 0) gives zero displacement, as in the direct solver.
  RelaxationReport solve(const Model& model, double lambda, Vector& free_displacement) const;

 private:
  double omega_;
  double tolerance_;
  long max_sweeps_;
};

}  // namespace latfrac
