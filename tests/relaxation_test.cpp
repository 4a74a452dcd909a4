// Over-relaxed Gauss-Seidel against the direct solver, the lithostatic column, the sweep cap.
#include "latfrac/solvers/relaxation.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "latfrac/base/stop_signal.h"
#include "latfrac/fracture/equilibrium_state.h"
#include "latfrac/mechanics/node_stress.h"
#include "latfrac/solvers/equilibrium.h"
#include "lithostatic_check.h"
#include "scenes.h"

using namespace latfrac;

namespace {

Vector direct_solution(Model& model, const SolverOptions& options, double lambda) {
  EquilibriumSolver solver(model, options);
  Vector u = Vector::Zero(model.dofs().free_count);
  solver.solve(lambda, u);
  return u;
}

double relative_difference(const Vector& a, const Vector& b) { return max_abs(a - b) / max_abs(b); }

double relative_residual(const Model& model, const Vector& u, double lambda) {
  const double load = max_abs(model.residual(Vector::Zero(model.dofs().free_count), lambda));
  return max_abs(model.residual(u, lambda)) / load;
}

// SmallKinematics that calls itself nonlinear: drives the solver's general sweep, which
// asks the law for every tension and tangent, on a problem with a known answer.
class FlaggedNonlinear final : public BondLaw {
 public:
  explicit FlaggedNonlinear(int dim) : BondLaw(dim), inner_(dim) {}
  BondDeformation deformation(const BondReference& r, const Vec3& du) const override {
    return inner_.deformation(r, du);
  }
  Vec3 tension(const PairSprings& p, PairState s, const Vec3& du) const override {
    return inner_.tension(p, s, du);
  }
  Mat3 tangent(const PairSprings& p, PairState s, const Vec3& du) const override {
    return inner_.tangent(p, s, du);
  }
  bool is_linear() const override { return false; }

 private:
  SmallKinematics inner_;
};

// Gives the model that law, keeping its contact law.
void flag_nonlinear(Model& model) {
  ModelEditor(model).set_laws(
      std::make_unique<FlaggedNonlinear>(model.dim()),
      model.has_contact() ? std::make_unique<ContactLaw>(model.lattice.spacing) : nullptr);
}

// The node nearest the lattice's centre (the lowest id on a tie).
std::int64_t node_nearest_centre(const Lattice& lattice) {
  std::int64_t centre = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    if ((lattice.positions[n] - lattice.extent / 2).norm() <
        (lattice.positions[centre] - lattice.extent / 2).norm())
      centre = n;
  }
  return centre;
}

}  // namespace

TEST_CASE("Relaxation reaches the direct solver's equilibrium", "[relaxation]") {
  const int dim = GENERATE(2, 3);
  Scene scene = dim == 2 ? testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true)
                         : testing::box_scene(3, 1.0, {4.0, 3.0, 3.0}, true);
  scene.solver.relaxation_tolerance = 1e-12;
  Model model = build_model(scene);
  const double lambda = 1e-4;
  const Vector direct = direct_solution(model, scene.solver, lambda);
  const RelaxationSolver relaxation(scene.solver);
  Vector u = Vector::Zero(model.dofs().free_count);
  const RelaxationReport report = relaxation.solve(model, lambda, u);
  INFO("dim " << dim << ": " << report.sweeps << " sweeps, residual " << report.relative_residual);
  CHECK(report.converged);
  CHECK(report.relative_residual <= 1e-12);
  // Independently of the solver's own bookkeeping: the model's residual.
  CHECK(relative_residual(model, u, lambda) <= 1e-12);
  CHECK(relative_difference(u, direct) < 1e-6);
}

TEST_CASE("The general sweep (any bond law) reaches the same equilibrium", "[relaxation]") {
  const int dim = GENERATE(2, 3);
  Scene scene = dim == 2 ? testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true)
                         : testing::box_scene(3, 1.0, {4.0, 3.0, 3.0}, true);
  scene.solver.relaxation_tolerance = 1e-12;
  Model model = build_model(scene);
  const double lambda = -1e-4;
  const Vector direct = direct_solution(model, scene.solver, lambda);
  flag_nonlinear(model);
  Vector u = Vector::Zero(model.dofs().free_count);
  const RelaxationReport report = RelaxationSolver(scene.solver).solve(model, lambda, u);
  CHECK(report.converged);
  CHECK(relative_residual(model, u, lambda) <= 1e-12);
  CHECK(relative_difference(u, direct) < 1e-6);
}

TEST_CASE("Relaxation with broken bonds and active contact springs", "[relaxation]") {
  Scene scene = testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true);
  scene.contact = Contact{};
  scene.solver.relaxation_tolerance = 1e-12;
  Model model = build_model(scene);
  // Break the bonds that cross x = 6.25 below mid-height; the horizontal ones, squeezed by
  // the walls at lambda < 0, keep their contact spring.
  const Lattice& lattice = model.lattice;
  int cut = 0, in_contact = 0;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Vec3& p = lattice.positions[lattice.bonds[b].i];
    const Vec3& q = lattice.positions[lattice.bonds[b].j];
    if ((p.x() - 6.25) * (q.x() - 6.25) >= 0 || p.z() + q.z() > 6.0) continue;
    const bool touching = std::abs(lattice.bond_direction[b].x()) > 0.9;
    ModelEditor(model).set_state(b, touching ? PairState::closed : PairState::open);
    ++cut;
    in_contact += touching;
  }
  REQUIRE(cut > 4);
  REQUIRE(in_contact > 1);
  const double lambda = -2e-4;
  const Vector direct = direct_solution(model, scene.solver, lambda);
  Vector u = Vector::Zero(model.dofs().free_count);
  const RelaxationReport report = RelaxationSolver(scene.solver).solve(model, lambda, u);
  CHECK(report.converged);
  CHECK(relative_residual(model, u, lambda) <= 1e-12);
  CHECK(relative_difference(u, direct) < 1e-6);
}

TEST_CASE("A node without bonds stays put and the report says not converged", "[relaxation]") {
  Scene scene = testing::box_scene(2, 1.0, {8.0, 0, 4.0}, true);
  scene.solver.relaxation_max_sweeps = 50;
  Model model = build_model(scene);
  const Lattice& lattice = model.lattice;
  // The node nearest the centre loses every bond: its weight meets no stiffness.
  const std::int64_t centre = node_nearest_centre(lattice);
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    if (lattice.bonds[b].i == centre || lattice.bonds[b].j == centre)
      ModelEditor(model).set_state(b, PairState::open);
  }
  for (const bool general : {false, true}) {
    if (general) flag_nonlinear(model);
    Vector u = Vector::Zero(model.dofs().free_count);
    RelaxationReport report;
    CHECK_NOTHROW(report = RelaxationSolver(scene.solver).solve(model, 0.0, u));
    CHECK_FALSE(report.converged);
    CHECK(report.sweeps == 50);
    CHECK(std::isfinite(report.relative_residual));
    CHECK(u.allFinite());
    CHECK(model.node_displacement(model.full_displacement(u, 0.0), centre).norm() == 0);
  }
}

TEST_CASE("A node held by one contact moves along its normal only, and never diverges",
          "[relaxation]") {
  // The node nearest the centre keeps one pair: a closed contact to a neighbour below it,
  // inclined, so its stiffness block kn n n' has rank 1. Its weight has a part along n,
  // which the contact balances, and a part across it, which nothing can. Treating each
  // axis as if the others stood still (omega F_c / B_cc) changes the contact by 2 omega
  // times its misfit per visit and diverges for omega > 1.
  const bool general = GENERATE(false, true);
  Scene scene = testing::box_scene(2, 1.0, {8.0, 0, 4.0}, true);
  scene.contact = Contact{};
  scene.solver.relaxation_max_sweeps = 200;
  Model model = build_model(scene);
  const Lattice& lattice = model.lattice;
  const std::int64_t centre = node_nearest_centre(lattice);
  std::int64_t kept = -1;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Bond& bond = lattice.bonds[b];
    if (bond.i != centre && bond.j != centre) continue;
    const std::int64_t other = bond.i == centre ? bond.j : bond.i;
    const Vec3 d = lattice.positions[other] - lattice.positions[centre];
    const bool below_inclined = kept < 0 && d.z() < 0 && std::abs(d.x()) > 0.1;
    ModelEditor(model).set_state(b, below_inclined ? PairState::closed : PairState::open);
    if (below_inclined) kept = b;
  }
  REQUIRE(kept >= 0);
  if (general) flag_nonlinear(model);
  Vector u = Vector::Zero(model.dofs().free_count);
  const RelaxationReport report = RelaxationSolver(scene.solver).solve(model, 0.0, u);
  INFO((general ? "general" : "linear") << " sweep: residual " << report.relative_residual);
  CHECK_FALSE(report.converged);  // the weight across the contact meets no stiffness
  CHECK(std::isfinite(report.relative_residual));
  REQUIRE(u.allFinite());
  // The node's out-of-balance force (external minus internal, summed over its pairs) has
  // no part along the contact's normal: statics along n holds.
  const Vector full = model.full_displacement(u, 0.0);
  const Vec3 n = lattice.bond_direction[kept];
  const Vec3 weight = model.node_displacement(model.external_force, centre);
  const Vec3 tension = model.bond_tension(full, kept);  // the internal force on end j
  const Vec3 internal = lattice.bonds[kept].j == centre ? tension : Vec3(-tension);
  const Vec3 out_of_balance = weight - internal;
  CHECK(std::abs(out_of_balance.dot(n)) < 1e-6 * weight.norm());
  CHECK(std::abs(out_of_balance.dot(n)) < 1e-3 * std::abs(weight.dot(n)));
}

TEST_CASE("A relaxed state that is not finite stops the run with a clear error", "[relaxation]") {
  // The run's equilibrium relaxes from its last state; a NaN there cannot be relaxed away,
  // and it must not reach a criterion (NaN in the events).
  Scene scene = testing::box_scene(2, 1.0, {8.0, 0, 4.0}, true);
  scene.solver.method = EquilibriumMethod::relaxation;
  scene.solver.relaxation_max_sweeps = 20;
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  EquilibriumState equilibrium(model, solver, scene.solver);
  Vector state = Vector::Zero(model.dofs().free_count);
  CHECK(equilibrium.displacement(1e-4).allFinite());  // a finite start relaxes
  state[state.size() / 2] = std::nan("");
  equilibrium.adopt(state, 0.0);
  CHECK_THROWS_WITH(equilibrium.displacement(1e-4), Catch::Contains("relaxation diverged"));
}

TEST_CASE("Relaxation from the exact solution stops at the first check", "[relaxation]") {
  Scene scene = testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true);
  Model model = build_model(scene);
  const double lambda = 2e-4;
  Vector u = direct_solution(model, scene.solver, lambda);
  const Vector exact = u;
  const RelaxationReport report = RelaxationSolver(scene.solver).solve(model, lambda, u);
  CHECK(report.converged);
  CHECK(report.sweeps <= RelaxationSolver::check_interval);
  CHECK(relative_difference(u, exact) < 1e-6);
}

TEST_CASE("A NaN in the state is never reported as converged", "[relaxation]") {
  // The residual check must see a NaN wherever it sits: std::max(largest, NaN) keeps
  // largest, so a plain running maximum skips it.
  const bool general = GENERATE(false, true);
  Scene scene = testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true);
  Model model = build_model(scene);
  const double lambda = 2e-4;
  Vector u = direct_solution(model, scene.solver, lambda);
  if (general) flag_nonlinear(model);
  u[u.size() / 2] = std::nan("");
  const RelaxationReport report = RelaxationSolver(scene.solver).solve(model, lambda, u);
  INFO((general ? "general" : "linear") << " sweep: residual " << report.relative_residual);
  CHECK_FALSE(report.converged);
  CHECK_FALSE(std::isfinite(report.relative_residual));
}

TEST_CASE("The sweep cap stops relaxation without an exception", "[relaxation]") {
  Scene scene = testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true);
  scene.solver.relaxation_max_sweeps = 3;
  Model model = build_model(scene);
  Vector u = Vector::Zero(model.dofs().free_count);
  RelaxationReport report;
  CHECK_NOTHROW(report = RelaxationSolver(scene.solver).solve(model, 1e-4, u));
  CHECK_FALSE(report.converged);
  CHECK(report.sweeps == 3);
  CHECK(report.relative_residual > scene.solver.relaxation_tolerance);
  CHECK(std::isfinite(report.relative_residual));
  CHECK(u.allFinite());
}

TEST_CASE("Plain Gauss-Seidel converges, and over-relaxation needs fewer sweeps", "[relaxation]") {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, true);
  Model model = build_model(scene);
  const double lambda = 1e-4;
  const Vector direct = direct_solution(model, scene.solver, lambda);
  auto relax = [&](double omega) {
    SolverOptions options = scene.solver;
    options.relaxation_omega = omega;
    Vector u = Vector::Zero(model.dofs().free_count);
    const RelaxationReport report = RelaxationSolver(options).solve(model, lambda, u);
    INFO("omega " << omega << ": " << report.sweeps << " sweeps");
    CHECK(report.converged);
    CHECK(relative_residual(model, u, lambda) <= options.relaxation_tolerance);
    CHECK(relative_difference(u, direct) < 1e-4);
    return report.sweeps;
  };
  const long gauss_seidel = relax(1.0);
  const long over_relaxed = relax(1.8);
  INFO("omega 1: " << gauss_seidel << " sweeps, omega 1.8: " << over_relaxed << " sweeps");
  CHECK(over_relaxed < gauss_seidel);
}

TEST_CASE("Relaxed lithostatic column: sigma_zz = -rho g depth at mid-body", "[relaxation]") {
  // The 2-D geometry of tests/lithostatic_test.cpp: 60 x 30 spacings.
  Scene scene = testing::box_scene(2, 500.0, {30e3, 0, 15e3}, true);
  scene.solver.relaxation_tolerance = 1e-9;
  Model model = build_model(scene);
  Vector u = Vector::Zero(model.dofs().free_count);
  const RelaxationReport report = RelaxationSolver(scene.solver).solve(model, 0.0, u);
  INFO(report.sweeps << " sweeps");
  REQUIRE(report.converged);
  const testing::LithostaticError error =
      testing::lithostatic_error(scene, model, model.full_displacement(u, 0.0));
  INFO(error.checked << " nodes, worst zz " << error.zz << ", worst xx " << error.xx);
  CHECK(error.checked > 20);
  CHECK(error.zz < 0.02);
  CHECK(error.xx < 0.02);
}

TEST_CASE("Relaxation rejects omega outside (0, 2)", "[relaxation]") {
  Scene scene = testing::box_scene(2, 1.0, {6.0, 0, 4.0}, true);
  Model model = build_model(scene);
  scene.solver.relaxation_omega = 2.0;
  CHECK_THROWS_WITH(RelaxationSolver(scene.solver), Catch::Contains("0 < relaxation_omega < 2"));
}

TEST_CASE("A stop requested during a relaxation solve ends the solve, not only the run",
          "[relaxation]") {
  // One solve can take minutes of sweeps (at nu = 1/4 one ran for ten minutes inside a
  // break's contact settling, deaf to SIGTERM): a requested stop ends it at its next
  // residual check, and the solve from scratch reaches equilibrium once the request is gone.
  Scene scene = testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true);
  scene.solver.relaxation_tolerance = 1e-12;
  Model model = build_model(scene);
  const RelaxationSolver relaxation(scene.solver);
  Vector u = Vector::Zero(model.dofs().free_count);
  request_stop();
  CHECK_THROWS_AS(relaxation.solve(model, 1e-4, u), StopWithinEvent);
  clear_stop_request();
  u.setZero();
  CHECK(relaxation.solve(model, 1e-4, u).converged);
}
