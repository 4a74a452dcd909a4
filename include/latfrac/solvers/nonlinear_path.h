// Events on a nonlinear equilibrium path: CVODE follows u(lambda), its root finding stops
// at the first bond to reach f = 1, and KINSOL corrects onto R(u, lambda) = 0 there.
//
// Differentiating R(u(lambda), lambda) = 0 gives the path's ODE in lambda,
//   du/dlambda = -J(u)^-1 dR/dlambda,   dR/dlambda = J_fp(u) rate_p,
// with J = dR/du the tangent on the free dofs and J_fp its coupling to the prescribed
// dofs, which move at the prescribed rates (model.h). dR/dlambda is exact: the bond
// law's jacobian() applied to the prescribed-rate vector. The factor is the solver's
// CholeskyFactor of the assembled stiffness, which for large kinematics is the symmetric
// part K of J (bond_law.h); iterative refinement x += K^-1 (b - J x), with J x computed
// bond by bond from the exact jacobian(), makes the solve exact (2-5 corrections at a
// few per cent strain). A linear law needs neither refinement nor more than one
// factorization per advance().
//
// Integrator: CV_ADAMS with SUNDIALS' fixed-point nonlinear solver. The right-hand side
// already contains J^-1, so the ODE is not stiff in lambda (its Jacobian is of the order
// of the relative change of stiffness per unit strain); Newton iterations (BDF) would
// need the Jacobian of J^-1 dR/dlambda, which is not available. Tolerances: relative
// sqrt(tolerance) clamped to [1e-8, 1e-4], absolute that times the displacement scale
// of the step (max of |u(from)| and |du/dlambda| |to - from|). The path only has to find
// the right crossing and a good start: lambda is then refined on corrected equilibria.
//
// Root function: one, g = max over intact bonds of f_b - 1 (FailureEvaluator). Its first
// zero is the first lambda where any bond reaches f = 1; it is continuous (only its slope
// jumps where the leading bond changes), which is all CVODE's root search needs, and it
// keeps CVODE's root bookkeeping O(1) instead of O(bonds).
//
// At the root: KINSOL (solver.solve) corrects u at lambda*, then secant steps in lambda on
// g evaluated at corrected equilibria move lambda* until |g| <= tolerance, so the event
// is located on the equilibrium path itself, not on the integrator's approximation.
// docs/large-kinematics.md has the cost.
#pragma once

#include <cstdint>

#include "latfrac/solvers/equilibrium.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/mechanics/model.h"
#include "latfrac/solvers/solver_options.h"

namespace latfrac {

struct PathEvent {
  double lambda = 0;
  std::int64_t bond = -1;  // -1: reached `to` with no event
};

// Work done by advance(), summed over calls.
struct PathStatistics {
  long steps = 0;                  // CVODE steps
  long rhs_evaluations = 0;        // du/dlambda evaluations
  long factorizations = 0;         // numeric factorizations of the tangent
  long refinement_iterations = 0;  // iterative-refinement corrections in those solves
  long root_evaluations = 0;       // evaluations of g
  long corrections = 0;            // KINSOL solves (the event and its secant steps)
};

class NonlinearPath {
 public:
  NonlinearPath(Model& model, EquilibriumSolver& solver, const FailureEvaluator& evaluator,
                const SolverOptions& options);

  // From an equilibrium free displacement at `from` (in/out), follows the path to `to`
  // and stops at the first lambda where an intact bond's failure index reaches 1. On
  // return the free displacement is the KINSOL-corrected equilibrium at the returned
  // lambda; the event's bond has the largest f there (ties: lowest id). When f >= 1
  // already at `from`, returns `from` at once. Throws Error naming the CVODE, KINSOL or
  // CHOLMOD call that failed.
  PathEvent advance(double from, double to, Vector& free_displacement);

  const PathStatistics& statistics() const { return statistics_; }

 private:
  friend struct PathIntegrator;
  // du/dlambda at the free displacement u and lambda.
  Vector path_derivative(const Vector& free_displacement, double lambda);
  // max f - 1 and the bond that holds it, at the free displacement and lambda.
  CriticalBond critical(const Vector& free_displacement, double lambda) const;
  // Moves (lambda, u) from a root of the integrated path onto the equilibrium path's root.
  PathEvent refine_event(double from, double to, double lambda, Vector& free_displacement);

  Model& model_;
  EquilibriumSolver& solver_;
  const FailureEvaluator& evaluator_;
  SolverOptions options_;
  PathStatistics statistics_;
  bool factor_is_tangent_ = false;  // linear law: the factor holds K for this advance()
};

}  // namespace latfrac
