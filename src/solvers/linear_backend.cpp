// The backend a problem file names (linear_backend.h).
#include "latfrac/solvers/linear_backend.h"

#include "latfrac/base/error.h"
#include "latfrac/solvers/cholesky.h"
#include "petsc_backend.h"

namespace latfrac {

std::unique_ptr<LinearBackend> make_linear_backend(const SolverOptions& options) {
  if (options.backend == LinearBackendKind::petsc) return make_petsc_backend();
  return std::make_unique<CholeskyFactor>(options.ordering);
}

}  // namespace latfrac
