// What a problem file's [solver] section asks for: the equilibrium method and its settings.
#pragma once

namespace latfrac {

enum class EquilibriumMethod { newton, relaxation };
enum class Ordering { metis, nesdis, amd };
// Who solves the linear systems (linear_backend.h): one CHOLMOD factor, or PETSc over MPI.
enum class LinearBackendKind { cholmod, petsc };

struct SolverOptions {
  EquilibriumMethod method = EquilibriumMethod::newton;
  double tolerance = 1e-10;  // residual, relative to the load
  int max_iterations = 50;   // Newton iterations
  Ordering ordering = Ordering::metis;
  LinearBackendKind backend = LinearBackendKind::cholmod;
  int refactor_every = 200;  // factor updates before a fresh factorization
  double relaxation_omega = 1.8;
  double relaxation_tolerance = 1e-8;
  long relaxation_max_sweeps = 100000;
};

}  // namespace latfrac
