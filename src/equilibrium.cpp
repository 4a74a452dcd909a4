// KINSOL Newton iteration with a CHOLMOD-backed SUNLinearSolver and SUNMatrix.
#include "latfrac/equilibrium.h"

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <string>

#include "latfrac/error.h"
#include "sundials_checks.h"

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
      s.factor_.factorize(s.stiffness_);
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
    return 0;
  }
  static int solve(SUNLinearSolver ls, SUNMatrix, N_Vector x, N_Vector b, realtype) {
    auto* k = static_cast<Kinsol*>(ls->content);
    EquilibriumSolver& s = *k->owner;
    as_vector(x) = as_vector(b);
    s.factor_.solve(N_VGetArrayPointer(x), N_VGetLength(x), 1);
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

EquilibriumSolver::EquilibriumSolver(Model& model, const SolverOptions& options)
    : model_(model), options_(options), stiffness_(model), factor_(options.ordering) {
  if (model.dofs.free_count > 0) {
    kinsol_ = std::make_unique<Kinsol>(this, static_cast<sunindextype>(model.dofs.free_count));
  }
  find_boundary_bonds();
}

void EquilibriumSolver::update_loads() {
  if (loads_current_) return;
  const std::int64_t n = model_.dofs.free_count;
  const Vector zero = Vector::Zero(n);
  auto free_part = [&](const Vector& full) {
    Vector part(n);
    for (std::int64_t dof = 0; dof < model_.dofs.dof_count(); ++dof) {
      if (model_.dofs.free_index[dof] >= 0) part[model_.dofs.free_index[dof]] = full[dof];
    }
    return part;
  };
  const Vector at0 = model_.internal_force(model_.full_displacement(zero, 0.0), boundary_bonds_);
  const Vector at1 = model_.internal_force(model_.full_displacement(zero, 1.0), boundary_bonds_);
  load0_ = free_part(model_.external_force - at0);
  load1_ = free_part(at0 - at1);
  loads_current_ = true;
}

EquilibriumSolver::~EquilibriumSolver() = default;

double EquilibriumSolver::load_scale(double lambda) {
  update_loads();
  return max_abs(load0_ + lambda * load1_);
}

void EquilibriumSolver::refactorize(const Vector& free_displacement, double lambda) {
  if (model_.dofs.free_count == 0) {
    factor_current_ = true;
    return;
  }
  last_solution_valid_ = false;
  stiffness_.assemble(model_, model_.full_displacement(free_displacement, lambda));
  factor_.factorize(stiffness_);
  ++counters_.factorizations;
  factor_current_ = true;
  updates_since_factorization_ = 0;
}

void EquilibriumSolver::update_factor(
    std::int64_t bond, const std::vector<std::pair<double, Vec3>>& weighted_directions,
    bool downdate) {
  loads_current_ = false;
  if (!factor_current_) return;  // the next factorization assembles the new stiffness
  if (updates_since_factorization_ >= options_.refactor_every) {
    factor_current_ = false;
    last_solution_valid_ = false;
    return;
  }
  std::vector<CholeskyFactor::Column> columns;
  for (const auto& [weight, direction] : weighted_directions) {
    if (weight <= 0) continue;
    CholeskyFactor::Column column;
    append_on_bond(bond, std::sqrt(weight) * direction, column);
    if (!column.empty()) columns.push_back(std::move(column));
  }
  try {
    factor_.update(columns, downdate);
  } catch (const Error&) {
    factor_current_ = false;  // refactorize; a real singularity is reported there
    last_solution_valid_ = false;
    return;
  }
  ++counters_.factor_updates;
  ++updates_since_factorization_;
  if (last_solution_valid_) record_force_change(bond, weighted_directions, downdate);
}

void EquilibriumSolver::remember_solution(const Vector& free_displacement, double lambda) {
  last_solution_ = free_displacement;
  last_lambda_ = lambda;
  last_solution_valid_ = true;
  pending_forces_.clear();
}

// The spring sum_k w_k d_k d_k' between the bond's nodes carried the internal force
// f = sum_k w_k (d_k . (u_j - u_i)) d_k on node j (and -f on node i) in the last solution.
// Removing it leaves the residual R = internal - external short by f, so the correction
// solves K du = f at j, -f at i; adding a spring (a contact closing) is the opposite.
void EquilibriumSolver::record_force_change(
    std::int64_t bond, const std::vector<std::pair<double, Vec3>>& weighted_directions,
    bool downdate) {
  const Bond& pair = model_.lattice.bonds[bond];
  const std::vector<int> axes = model_.lattice.axes();
  const int dim = model_.dim();
  auto displacement = [&](std::int64_t node, int c) {
    const std::int64_t dof = node * dim + c;
    const std::int64_t f = model_.dofs.free_index[dof];
    return f >= 0 ? last_solution_[f]
                  : model_.dofs.prescribed_base[dof] + last_lambda_ * model_.dofs.prescribed_rate[dof];
  };
  Vec3 stretch = Vec3::Zero();  // u_j - u_i on the lattice's axes
  for (int c = 0; c < dim; ++c)
    stretch[axes[c]] = displacement(pair.j, c) - displacement(pair.i, c);
  Vec3 force = Vec3::Zero();
  for (const auto& [weight, direction] : weighted_directions)
    force += weight * direction.dot(stretch) * direction;
  append_on_bond(bond, downdate ? force : Vec3(-force), pending_forces_);
}

void EquilibriumSolver::append_on_bond(std::int64_t bond, const Vec3& v,
                                       CholeskyFactor::Column& column) const {
  const Bond& pair = model_.lattice.bonds[bond];
  const std::vector<int> axes = model_.lattice.axes();
  const int dim = model_.dim();
  for (int c = 0; c < dim; ++c) {
    const double value = v[axes[c]];
    if (value == 0) continue;
    const std::int64_t fj = model_.dofs.free_index[pair.j * dim + c];
    const std::int64_t fi = model_.dofs.free_index[pair.i * dim + c];
    if (fj >= 0) column.push_back({fj, value});
    if (fi >= 0) column.push_back({fi, -value});
  }
}

// The bond's stiffness kn n0 n0' + ks (I - n0 n0') as weighted orthonormal directions.
void EquilibriumSolver::remove_bond(std::int64_t bond) {
  const Vec3& n0 = model_.lattice.bond_direction[bond];
  const double kn = model_.normal_stiffness[bond], ks = model_.shear_stiffness[bond];
  std::vector<std::pair<double, Vec3>> directions{{kn, n0}};
  if (model_.dim() == 2) {
    directions.push_back({ks, Vec3(-n0.z(), 0, n0.x())});
  } else {
    const Vec3 helper = std::abs(n0.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 first = n0.cross(helper).normalized();
    directions.push_back({ks, first});
    directions.push_back({ks, n0.cross(first)});
  }
  update_factor(bond, directions, /*downdate=*/true);
}

void EquilibriumSolver::set_contact(std::int64_t bond, bool active) {
  update_factor(bond, {{model_.normal_stiffness[bond], model_.lattice.bond_direction[bond]}},
                /*downdate=*/!active);
}

// Without load (no gravity at lambda = 0) the solution is 0 and any finite result passes;
// a NaN from a singular factor must not.
double EquilibriumSolver::relative_residual(const Vector& free_displacement, double lambda) {
  const double load = load_scale(lambda);
  const double residual = max_abs(model_.residual(free_displacement, lambda));
  if (load == 0) return std::isfinite(residual) ? 0 : residual;
  return residual / load;
}

namespace {

std::string ill_conditioned(double lambda, double residual, double tolerance) {
  return "equilibrium at lambda " + std::to_string(lambda) + ": the residual after a fresh " +
         "factorization is " + std::to_string(residual) + " of the load (tolerance " +
         std::to_string(tolerance) + "): the stiffness is too ill-conditioned";
}

}  // namespace

AffinePath EquilibriumSolver::checked_affine_path(double lambda) {
  AffinePath path = affine_path();
  if (relative_residual(path.at(lambda), lambda) <= options_.tolerance) return path;
  factor_current_ = false;
  path = affine_path();
  const double fresh = relative_residual(path.at(lambda), lambda);
  if (fresh > options_.tolerance) throw Error(ill_conditioned(lambda, fresh, options_.tolerance));
  return path;
}

Vector EquilibriumSolver::checked_solve(double lambda) {
  const std::int64_t n = model_.dofs.free_count;
  if (last_solution_valid_ && factor_current_ && lambda == last_lambda_ && n > 0) {
    Vector correction(n);
    if (factor_.solve_sparse(pending_forces_, correction.data())) {
      ++counters_.solves;
      ++counters_.correction_solves;
      Vector u = last_solution_ + correction;
      if (relative_residual(u, lambda) <= options_.tolerance) {
        remember_solution(u, lambda);
        return u;
      }
    }
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!factor_current_) refactorize(Vector::Zero(n), 0.0);
    update_loads();
    Vector u = load0_ + lambda * load1_;
    if (n > 0) factor_.solve(u.data(), n, 1);
    ++counters_.solves;
    const double residual = relative_residual(u, lambda);
    if (residual <= options_.tolerance) {
      remember_solution(u, lambda);
      return u;
    }
    if (attempt == 1) throw Error(ill_conditioned(lambda, residual, options_.tolerance));
    factor_current_ = false;
  }
  return {};
}

// With every dof prescribed (everything held) there is nothing to analyse or solve.
void EquilibriumSolver::supports_changed() {
  last_solution_valid_ = false;  // the free dofs are others now
  stiffness_ = StiffnessMatrix(model_);
  kinsol_.reset();
  if (model_.dofs.free_count > 0) {
    factor_.analyze(stiffness_);
    kinsol_ = std::make_unique<Kinsol>(this, static_cast<sunindextype>(model_.dofs.free_count));
  }
  factor_current_ = false;
  find_boundary_bonds();
}

void EquilibriumSolver::find_boundary_bonds() {
  loads_current_ = false;
  boundary_bonds_.clear();
  const int dim = model_.dim();
  auto held = [&](std::int64_t node) {
    for (int c = 0; c < dim; ++c) {
      if (model_.dofs.free_index[node * dim + c] < 0) return true;
    }
    return false;
  };
  for (std::int64_t b = 0; b < model_.lattice.bond_count(); ++b) {
    const Bond& bond = model_.lattice.bonds[b];
    if (held(bond.i) || held(bond.j)) boundary_bonds_.push_back(b);
  }
}

EquilibriumReport EquilibriumSolver::solve(double lambda, Vector& free_displacement) {
  EquilibriumReport report;
  const double load = load_scale(lambda);
  if (load == 0 || model_.dofs.free_count == 0) {
    free_displacement.setZero(model_.dofs.free_count);
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
  const bool reuse = model_.law->is_linear() && factor_current_;
  check_flag(KINSetNoInitSetup(k.memory, reuse ? SUNTRUE : SUNFALSE), "KINSetNoInitSetup");
  // Exact Newton (a fresh tangent every iteration) on a nonlinear problem; a linear one
  // keeps its factor. KINSOL counts iterations across calls, so "never" must be large.
  const long setup_every = model_.law->is_linear() ? 1000000000L : 1L;
  check_flag(KINSetMaxSetupCalls(k.memory, setup_every), "KINSetMaxSetupCalls");
  const int strategy = model_.law->is_linear() ? KIN_NONE : KIN_LINESEARCH;
  const int flag = KINSol(k.memory, k.unknowns, strategy, k.unit_scale, k.residual_scale);
  if (flag < 0) {
    std::string message = std::string("KINSol failed (") + flag_name(flag) + ")";
    if (!k.last_message.empty()) message += ": " + k.last_message;
    if (k.singular_unknown >= 0) throw SingularStiffness(message, k.singular_unknown);
    throw Error(message);
  }
  free_displacement = as_vector(k.unknowns);
  check_flag(KINGetNumNonlinSolvIters(k.memory, &report.newton_iterations),
             "KINGetNumNonlinSolvIters");
  check_flag(KINGetNumFuncEvals(k.memory, &report.residual_evaluations), "KINGetNumFuncEvals");
  double scaled_norm = 0;
  check_flag(KINGetFuncNorm(k.memory, &scaled_norm), "KINGetFuncNorm");
  const bool evaluated = k.last_unknowns.size() == free_displacement.size() &&
                         k.last_unknowns == free_displacement;
  report.relative_residual =
      max_abs(evaluated ? k.last_residual : model_.residual(free_displacement, lambda)) / load;
  if (report.relative_residual > options_.tolerance) {
    throw Error("KINSol stopped (" + flag_name(flag) + ") with the residual at " +
                std::to_string(report.relative_residual) + " of the load, above the tolerance " +
                std::to_string(options_.tolerance));
  }
  return report;
}

AffinePath EquilibriumSolver::affine_path() {
  if (!model_.law->is_linear()) throw Error("affine_path: the bond law is not linear");
  const std::int64_t n = model_.dofs.free_count;
  if (!factor_current_) refactorize(Vector::Zero(n), 0.0);
  update_loads();
  Eigen::MatrixXd rhs(n, 2);
  rhs.col(0) = load0_;
  rhs.col(1) = load1_;
  if (n > 0) factor_.solve(rhs.data(), n, 2);
  ++counters_.solves;
  return {rhs.col(0), rhs.col(1)};
}

}  // namespace latfrac
