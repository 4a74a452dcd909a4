// KINSOL's Newton iteration for the equilibrium solver, with a SUNLinearSolver and a
// SUNMatrix that forward to its stiffness and CHOLMOD factor.
#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <iomanip>
#include <sstream>
#include <string>

#include "latfrac/base/error.h"
#include "latfrac/base/phase_times.h"
#include "latfrac/solvers/equilibrium.h"
#include "sundials_checks.h"
#include "unsymmetric.h"

namespace latfrac {
namespace {

using sundials::as_vector;
using sundials::check_flag;
using sundials::check_pointer;

std::string flag_name(int flag) { return sundials::flag_name(KINGetReturnFlagName(flag)); }

}  // namespace

// KINSOL's memory, vectors, and the matrix and linear solver that forward to the
// EquilibriumSolver. The SUNMatrix carries no data: the stiffness lives in the solver.
struct EquilibriumSolver::Kinsol {
  EquilibriumSolver* owner = nullptr;
  SUNContext context = nullptr;
  void* memory = nullptr;
  N_Vector unknowns = nullptr, unit_scale = nullptr, residual_scale = nullptr;
  SUNMatrix jacobian = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  double lambda = 0;
  std::string last_message;
  long long singular_unknown = -1;  // set when a factorization found no stiffness

  // KINSOL's last residual and where it was evaluated: the final check reuses it when
  // KINSOL stopped at that point (one bond loop fewer per solve).
  Vector last_unknowns, last_residual;

  static int residual(N_Vector u, N_Vector f, void* data) {
    auto* k = static_cast<Kinsol*>(data);
    as_vector(f) = k->owner->model_.residual(as_vector(u), k->lambda);
    k->last_unknowns = as_vector(u);
    k->last_residual = as_vector(f);
    return 0;
  }
  static int jacobian_fn(N_Vector u, N_Vector, SUNMatrix, void* data, N_Vector, N_Vector) {
    auto* k = static_cast<Kinsol*>(data);
    EquilibriumSolver& s = *k->owner;
    s.stiffness_.assemble(s.model_, s.model_.full_displacement(as_vector(u), k->lambda));
    s.factor_current_ = false;
    return 0;
  }
  static int setup(SUNLinearSolver ls, SUNMatrix) {
    auto* k = static_cast<Kinsol*>(ls->content);
    EquilibriumSolver& s = *k->owner;
    try {
      s.factor_->factorize(s.stiffness_);
    } catch (const SingularStiffness& e) {
      k->last_message = e.what();
      k->singular_unknown = e.unknown();
      return -1;  // unrecoverable
    } catch (const Error& e) {
      k->last_message = e.what();
      return -1;
    }
    ++s.counters_.factorizations;
    s.factor_current_ = true;
    s.factored_states_.clear();  // a tangent at some displacement: no history to replay
    return 0;
  }
  static int solve(SUNLinearSolver ls, SUNMatrix, N_Vector x, N_Vector b, realtype) {
    auto* k = static_cast<Kinsol*>(ls->content);
    EquilibriumSolver& s = *k->owner;
    as_vector(x) = as_vector(b);
    s.factor_->solve(N_VGetArrayPointer(x), N_VGetLength(x), 1);
    ++s.counters_.solves;
    return 0;
  }
  static void error_handler(int, const char* module, const char* function, char* message,
                            void* data) {
    auto* k = static_cast<Kinsol*>(data);
    if (k->last_message.empty()) {
      k->last_message = std::string(module) + " " + function + ": " + message;
    }
  }

  Kinsol(EquilibriumSolver* solver, sunindextype unknowns_count) : owner(solver) {
    check_flag(SUNContext_Create(nullptr, &context), "SUNContext_Create");
    unknowns = check_pointer(N_VNew_Serial(unknowns_count, context), "N_VNew_Serial");
    unit_scale = check_pointer(N_VNew_Serial(unknowns_count, context), "N_VNew_Serial");
    residual_scale = check_pointer(N_VNew_Serial(unknowns_count, context), "N_VNew_Serial");
    N_VConst(1.0, unit_scale);

    jacobian = check_pointer(SUNMatNewEmpty(context), "SUNMatNewEmpty");
    jacobian->ops->getid = [](SUNMatrix) { return SUNMATRIX_CUSTOM; };
    jacobian->ops->zero = [](SUNMatrix) { return 0; };  // the Jacobian routine refills every value
    jacobian->ops->destroy = [](SUNMatrix a) { SUNMatFreeEmpty(a); };

    linear_solver = check_pointer(SUNLinSolNewEmpty(context), "SUNLinSolNewEmpty");
    linear_solver->content = this;
    linear_solver->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
    linear_solver->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
    linear_solver->ops->setup = setup;
    linear_solver->ops->solve = solve;
    linear_solver->ops->free = [](SUNLinearSolver ls) { return SUNLinSolFreeEmpty(ls), 0; };

    memory = check_pointer(KINCreate(context), "KINCreate");
    check_flag(KINSetErrHandlerFn(memory, error_handler, this), "KINSetErrHandlerFn");
    check_flag(KINInit(memory, residual, unknowns), "KINInit");
    check_flag(KINSetUserData(memory, this), "KINSetUserData");
    check_flag(KINSetLinearSolver(memory, linear_solver, jacobian), "KINSetLinearSolver");
    check_flag(KINSetJacFn(memory, jacobian_fn), "KINSetJacFn");
    // The default maximum step (1000 |u0|) is zero from a zero initial guess.
    check_flag(KINSetMaxNewtonStep(memory, 1e30), "KINSetMaxNewtonStep");
    check_flag(KINSetScaledStepTol(memory, 1e-300), "KINSetScaledStepTol");
  }

  ~Kinsol() {
    KINFree(&memory);
    if (linear_solver) SUNLinSolFree(linear_solver);
    if (jacobian) SUNMatDestroy(jacobian);
    N_VDestroy(unknowns);
    N_VDestroy(unit_scale);
    N_VDestroy(residual_scale);
    SUNContext_Free(&context);
  }
};

// The constructor and destructor live here, where Kinsol is a complete type.
EquilibriumSolver::EquilibriumSolver(Model& model, const SolverOptions& options)
    : model_(model), editor_(model), options_(options), stiffness_(model), factor_(make_linear_backend(options)) {
  reset_kinsol();
  find_boundary_bonds();
  // Analysed now (not at the first factorization) so that holds can inherit the order.
  if (model_.dofs().free_count > 0) analyse({});
}

EquilibriumSolver::~EquilibriumSolver() = default;  // Unsymmetric: unsymmetric.h

// KINSOL's memory is sized for the free dofs: none without free dofs.
void EquilibriumSolver::reset_kinsol() {
  kinsol_.reset();
  if (model_.dofs().free_count > 0)
    kinsol_ = std::make_unique<Kinsol>(this, static_cast<sunindextype>(model_.dofs().free_count));
}

EquilibriumReport EquilibriumSolver::solve(double lambda, Vector& free_displacement) {
  const ScopedPhase phase(Phase::solve);
  EquilibriumReport report;
  const double load = load_scale(lambda);
  if (load == 0 || model_.dofs().free_count == 0) {
    free_displacement.setZero(model_.dofs().free_count);
    return report;
  }
  Kinsol& k = *kinsol_;
  k.lambda = lambda;
  k.last_unknowns.resize(0);
  k.last_message.clear();
  k.singular_unknown = -1;
  as_vector(k.unknowns) = free_displacement;
  N_VConst(1.0 / load, k.residual_scale);
  check_flag(KINSetFuncNormTol(k.memory, options_.tolerance), "KINSetFuncNormTol");
  check_flag(KINSetNumMaxIters(k.memory, options_.max_iterations), "KINSetNumMaxIters");
  // A linear problem whose factor is current needs no new factorization.
  const bool reuse = model_.is_linear() && factor_current_;
  check_flag(KINSetNoInitSetup(k.memory, reuse ? SUNTRUE : SUNFALSE), "KINSetNoInitSetup");
  // Exact Newton (a fresh tangent every iteration) on a nonlinear problem; a linear one
  // keeps its factor. KINSOL counts iterations across calls, so "never" must be large.
  const long setup_every = model_.is_linear() ? 1000000000L : 1L;
  check_flag(KINSetMaxSetupCalls(k.memory, setup_every), "KINSetMaxSetupCalls");
  const int strategy = model_.is_linear() ? KIN_NONE : KIN_LINESEARCH;
  const int flag = KINSol(k.memory, k.unknowns, strategy, k.unit_scale, k.residual_scale);
  // Large kinematics: Newton's last iterate at the rounding floor of this system (its
  // tangent freshly factorized at every iteration), and within max_rounding_excess of the
  // tolerance, is accepted as the linear route accepts it after a fresh factorization
  // (fresh_solve_missed): KINSOL stops there with steps too small to go on, or out of
  // iterations, and no iterate can do better.
  const auto at_floor = [&](const Vector& u, double residual) {
    return !model_.is_linear() && accepted_at_floor(u, lambda, residual);
  };
  const auto count_iterations = [&] {
    check_flag(KINGetNumNonlinSolvIters(k.memory, &report.newton_iterations),
               "KINGetNumNonlinSolvIters");
    check_flag(KINGetNumFuncEvals(k.memory, &report.residual_evaluations), "KINGetNumFuncEvals");
  };
  if (flag < 0) {
    std::string message = std::string("KINSol failed (") + flag_name(flag) + ")";
    if (!k.last_message.empty()) message += ": " + k.last_message;
    if (k.singular_unknown >= 0) throw SingularStiffness(message, k.singular_unknown);
    const Vector last = as_vector(k.unknowns);
    const double residual = max_abs(model_.residual(last, lambda)) / load;
    if (at_floor(last, residual)) {
      free_displacement = last;
      count_iterations();
      report.relative_residual = residual;
      return report;
    }
    // Say where, how far from equilibrium the last iterate was, and what may help: KINSOL's
    // own words name neither the loading nor the settings.
    std::ostringstream where;
    where << std::scientific << std::setprecision(2)
          << "equilibrium (Newton, KINSOL) not reached at lambda " << lambda;
    if (std::isfinite(residual))
      where << ": the last iterate's residual is " << residual
            << " of the load, against solver.tolerance " << options_.tolerance;
    where << " (" << message << "). A body this ill-conditioned (tall and thin, or far from "
          << "equilibrium in large kinematics) may need a larger solver.tolerance, more "
          << "solver.max_iterations (now " << options_.max_iterations
          << ") or smaller loading steps";
    throw Error(where.str());
  }
  free_displacement = as_vector(k.unknowns);
  count_iterations();
  const bool evaluated = k.last_unknowns.size() == free_displacement.size() &&
                         k.last_unknowns == free_displacement;
  report.relative_residual =
      max_abs(evaluated ? k.last_residual : model_.residual(free_displacement, lambda)) / load;
  if (report.relative_residual > options_.tolerance &&
      !at_floor(free_displacement, report.relative_residual)) {
    std::ostringstream message;
    message << std::scientific << std::setprecision(2)
            << "equilibrium (Newton, KINSOL) not reached at lambda " << lambda
            << ": KINSOL stopped (" << flag_name(flag) << ") with the residual at "
            << report.relative_residual << " of the load, above solver.tolerance "
            << options_.tolerance
            << " (its steps had become too small to go on: the rounding floor of this system, "
               "or a law far from equilibrium). A larger solver.tolerance, or smaller loading "
               "steps, may help";
    throw Error(message.str());
  }
  return report;
}

}  // namespace latfrac
