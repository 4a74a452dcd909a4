// The equilibrium path in lambda by CVODE (Adams, fixed point), events by its root finding.
#include "latfrac/solvers/nonlinear_path.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "latfrac/base/error.h"
#include "latfrac/base/phase_times.h"
#include "sundials_checks.h"

namespace latfrac {
namespace {

using sundials::as_vector;
using sundials::check_flag;
using sundials::check_pointer;

std::string flag_name(int flag) { return sundials::flag_name(CVodeGetReturnFlagName(flag)); }


// Relative tolerance of the integration: the path only has to find the right crossing
// and a good starting point for the correction (nonlinear_path.h).
double path_tolerance(const SolverOptions& options) {
  return std::clamp(std::sqrt(options.tolerance), 1e-8, 1e-4);
}

// The full vector with `free` on the free dofs and zero on the prescribed ones.
Vector embed_free(const Model& model, const Vector& free) {
  Vector full = Vector::Zero(model.dofs().dof_count());
  for (std::int64_t dof = 0; dof < model.dofs().dof_count(); ++dof) {
    if (model.dofs().free_index[dof] >= 0) full[dof] = free[model.dofs().free_index[dof]];
  }
  return full;
}

// The full vector with the prescribed rates on the prescribed dofs, zero elsewhere.
Vector prescribed_rates(const Model& model) {
  Vector full = Vector::Zero(model.dofs().dof_count());
  for (std::int64_t dof = 0; dof < model.dofs().dof_count(); ++dof) {
    if (model.dofs().free_index[dof] < 0) full[dof] = model.dofs().prescribed_rate[dof];
  }
  return full;
}

// The derivative of the internal force on the free dofs at the full displacement u in the
// direction v (full vector): sum over bonds of +-T(du) (v_j - v_i), with the law's exact
// jacobian of each pair's law in its state, as Model::add_bond_force has them.
Vector directional_derivative(const Model& model, const Vector& displacement,
                              const Vector& direction) {
  Vector result = Vector::Zero(model.dofs().free_count);
  const int d = model.dim();
  const Lattice& lattice = model.lattice;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const InteractionLaw* law = model.law_of(b);
    if (model.state(b) == PairState::open || !law) continue;
    const Vec3 relative_direction = model.relative_motion(direction, b);
    if (relative_direction.isZero(0.0)) continue;
    const Mat3 tangent =
        law->jacobian(model.springs(b), model.state(b), model.bond_displacement(displacement, b));
    const Vec3 change = tangent * relative_direction;
    const Bond& bond = lattice.bonds[b];
    for (int c = 0; c < d; ++c) {
      const double component = change[d == 2 ? 2 * c : c];
      const std::int64_t fj = model.dofs().free_index[bond.j * d + c];
      const std::int64_t fi = model.dofs().free_index[bond.i * d + c];
      if (fj >= 0) result[fj] += component;
      if (fi >= 0) result[fi] -= component;
    }
  }
  return result;
}

}  // namespace

// CVODE's memory and vectors for one advance(), and the callbacks that forward to the path.
struct PathIntegrator {
  NonlinearPath* path = nullptr;
  SUNContext context = nullptr;
  N_Vector state = nullptr;
  SUNNonlinearSolver fixed_point = nullptr;
  void* memory = nullptr;
  std::string last_message;

  static int rhs(realtype lambda, N_Vector u, N_Vector derivative, void* data) {
    auto* p = static_cast<PathIntegrator*>(data);
    try {
      as_vector(derivative) = p->path->path_derivative(as_vector(u), lambda);
    } catch (const std::exception& e) {
      p->last_message = e.what();
      return -1;  // unrecoverable: a singular tangent does not heal with a smaller step
    }
    return 0;
  }
  static int root(realtype lambda, N_Vector u, realtype* g, void* data) {
    auto* p = static_cast<PathIntegrator*>(data);
    try {
      g[0] = p->path->critical(as_vector(u), lambda).index - 1;
      ++p->path->statistics_.root_evaluations;
    } catch (const std::exception& e) {
      p->last_message = e.what();
      return -1;
    }
    return 0;
  }
  static void error_handler(int, const char* module, const char* function, char* message,
                            void* data) {
    auto* p = static_cast<PathIntegrator*>(data);
    if (p->last_message.empty())
      p->last_message = std::string(module) + " " + function + ": " + message;
  }

  PathIntegrator(NonlinearPath* owner, const Vector& start, double from, double to, double relative,
                 double absolute)
      : path(owner) {
    try {
      create(start, from, to, relative, absolute);
    } catch (...) {
      release();
      throw;
    }
  }
  ~PathIntegrator() { release(); }

  void create(const Vector& start, double from, double to, double relative, double absolute) {
    check_flag(SUNContext_Create(nullptr, &context), "SUNContext_Create");
    state = check_pointer(N_VNew_Serial(static_cast<sunindextype>(start.size()), context),
                          "N_VNew_Serial");
    as_vector(state) = start;
    memory = check_pointer(CVodeCreate(CV_ADAMS, context), "CVodeCreate");
    check_flag(CVodeSetErrHandlerFn(memory, error_handler, this), "CVodeSetErrHandlerFn");
    check_flag(CVodeInit(memory, rhs, from, state), "CVodeInit");
    check_flag(CVodeSetUserData(memory, this), "CVodeSetUserData");
    check_flag(CVodeSStolerances(memory, relative, absolute), "CVodeSStolerances");
    fixed_point =
        check_pointer(SUNNonlinSol_FixedPoint(state, 0, context), "SUNNonlinSol_FixedPoint");
    check_flag(CVodeSetNonlinearSolver(memory, fixed_point), "CVodeSetNonlinearSolver");
    check_flag(CVodeRootInit(memory, 1, root), "CVodeRootInit");
    check_flag(CVodeSetStopTime(memory, to), "CVodeSetStopTime");
    check_flag(CVodeSetMaxNumSteps(memory, 100000), "CVodeSetMaxNumSteps");
  }

  void release() {
    if (memory) CVodeFree(&memory);
    if (fixed_point) SUNNonlinSolFree(fixed_point);
    if (state) N_VDestroy(state);
    if (context) SUNContext_Free(&context);
    fixed_point = nullptr;
    state = nullptr;
  }
  PathIntegrator(const PathIntegrator&) = delete;
  PathIntegrator& operator=(const PathIntegrator&) = delete;
};

NonlinearPath::NonlinearPath(Model& model, EquilibriumSolver& solver,
                             const FailureEvaluator& evaluator, const SolverOptions& options)
    : model_(model), solver_(solver), evaluator_(evaluator), options_(options) {}

CriticalBond NonlinearPath::critical(const Vector& free_displacement, double lambda) const {
  return evaluator_.most_critical(model_, model_.full_displacement(free_displacement, lambda));
}

// du/dlambda = -J^-1 dR/dlambda. The factor holds the assembled stiffness K (the symmetric
// part of J); for a nonlinear law, iterative refinement with the exact product J x makes
// the solve J x = b exact to well below the integration tolerance.
Vector NonlinearPath::path_derivative(const Vector& free_displacement, double lambda) {
  ++statistics_.rhs_evaluations;
  const Vector displacement = model_.full_displacement(free_displacement, lambda);
  const bool linear = model_.is_linear();
  if (!linear || !factor_is_tangent_) {
    solver_.stiffness().assemble(model_, displacement);
    solver_.factor().factorize(solver_.stiffness());
    ++statistics_.factorizations;
    factor_is_tangent_ = linear;
  }
  const std::int64_t n = model_.dofs().free_count;
  const Vector load_rate = -directional_derivative(model_, displacement, prescribed_rates(model_));
  Vector rate = load_rate;
  if (n == 0) return rate;
  solver_.factor().solve(rate.data(), n, 1);
  if (linear) return rate;

  // Refine to well below the integration tolerance; rounding may stop the refinement
  // earlier, which is harmless while the misfit is below a tenth of that tolerance.
  const double load_size = max_abs(load_rate);
  const double target = 1e-3 * path_tolerance(options_) * load_size;
  const double acceptable = 1e-1 * path_tolerance(options_) * load_size;
  double previous = load_size;
  for (int iteration = 0; iteration < 50; ++iteration) {
    Vector misfit =
        load_rate - directional_derivative(model_, displacement, embed_free(model_, rate));
    const double size = max_abs(misfit);
    if (size <= target) return rate;
    if (iteration > 0 && !(size < 0.9 * previous)) {
      if (size <= acceptable) return rate;
      throw Error(
          "path derivative at lambda " + std::to_string(lambda) +
          ": iterative refinement with the symmetric part of the tangent stalled (misfit " +
          std::to_string(size / load_size) +
          " of the load rate): the bonds have rotated too far for the symmetric approximation");
    }
    previous = size;
    solver_.factor().solve(misfit.data(), n, 1);
    rate += misfit;
    ++statistics_.refinement_iterations;
  }
  throw Error("path derivative at lambda " + std::to_string(lambda) +
              ": iterative refinement did not converge in 50 iterations");
}

// Secant steps in lambda on g = max f - 1 at KINSOL-corrected equilibria, starting from a
// root of the integrated path (u already corrected at lambda). The first slope comes from
// the tangent predictor u + h du/dlambda.
PathEvent NonlinearPath::refine_event(double from, double to, double lambda,
                                      Vector& free_displacement) {
  const double low = std::min(from, to), high = std::max(from, to);
  const double f_tolerance = std::max(options_.tolerance, 1e-14);
  CriticalBond leader = critical(free_displacement, lambda);
  double g = leader.index - 1;
  if (std::abs(g) > f_tolerance) {
    const Vector rate = path_derivative(free_displacement, lambda);
    const double span = std::max(std::abs(lambda), std::abs(to - from));
    const double h = (g > 0 ? -1.0 : 1.0) * 1e-7 * span;
    double slope = (critical(free_displacement + h * rate, lambda + h).index - 1 - g) / h;
    for (int iteration = 0; iteration < 12 && std::abs(g) > f_tolerance; ++iteration) {
      if (!(slope > 0) || !std::isfinite(slope)) break;
      const double next = std::clamp(lambda - g / slope, low, high);
      if (next == lambda) break;
      Vector next_displacement = free_displacement + (next - lambda) * rate;
      solver_.solve(next, next_displacement);
      ++statistics_.corrections;
      const CriticalBond next_leader = critical(next_displacement, next);
      const double next_g = next_leader.index - 1;
      slope = (next_g - g) / (next - lambda);
      lambda = next;
      free_displacement = next_displacement;
      leader = next_leader;
      g = next_g;
    }
  }
  // The corrected path does not reach f = 1 before `to`: no event after all.
  if (g < -f_tolerance && lambda == to) return {to, -1};
  return {lambda, leader.bond};
}

PathEvent NonlinearPath::advance(double from, double to, Vector& free_displacement) {
  const ScopedPhase phase(Phase::solve);
  factor_is_tangent_ = false;  // the intact bonds may have changed since the last call
  const CriticalBond start = critical(free_displacement, from);
  if (start.bond >= 0 && start.index >= 1) return {from, start.bond};
  if (to == from || model_.dofs().free_count == 0) {
    solver_.solve(to, free_displacement);
    return {to, -1};
  }

  const double relative = path_tolerance(options_);
  const Vector initial_rate = path_derivative(free_displacement, from);
  const double scale =
      std::max({max_abs(free_displacement), max_abs(initial_rate) * std::abs(to - from),
                1e-15 * model_.lattice.spacing});
  PathIntegrator integrator(this, free_displacement, from, to, relative, relative * scale);
  double reached = from;
  const int flag = CVode(integrator.memory, to, integrator.state, &reached, CV_NORMAL);
  long steps = 0;
  check_flag(CVodeGetNumSteps(integrator.memory, &steps), "CVodeGetNumSteps");
  statistics_.steps += steps;
  if (flag < 0) {
    std::string message =
        "CVode failed (" + flag_name(flag) + ") at lambda " + std::to_string(reached);
    if (!integrator.last_message.empty()) message += ": " + integrator.last_message;
    throw Error(message);
  }
  free_displacement = as_vector(integrator.state);
  const double lambda = flag == CV_ROOT_RETURN ? reached : to;
  solver_.solve(lambda, free_displacement);
  ++statistics_.corrections;
  if (flag != CV_ROOT_RETURN && critical(free_displacement, to).index < 1) return {to, -1};
  return refine_event(from, to, lambda, free_displacement);
}

}  // namespace latfrac
