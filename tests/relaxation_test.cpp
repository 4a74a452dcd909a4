// Over-relaxed Gauss-Seidel against the direct solver, the lithostatic column, the sweep cap.
#include "latfrac/solvers/relaxation.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "latfrac/solvers/equilibrium.h"
#include "latfrac/mechanics/node_stress.h"
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

double relative_difference(const Vector& a, const Vector& b) {
  return max_abs(a - b) / max_abs(b);
}

double relative_residual(const Model& model, const Vector& u, double lambda) {
  const double load =
      max_abs(model.residual(Vector::Zero(model.dofs().free_count), lambda));
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
  ModelEditor(model).set_laws(std::make_unique<FlaggedNonlinear>(model.dim()),
                              model.has_contact()
                                  ? std::make_unique<ContactLaw>(model.lattice.spacing)
                                  : nullptr);
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
  std::int64_t centre = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    if ((lattice.positions[n] - lattice.extent / 2).norm() <
        (lattice.positions[centre] - lattice.extent / 2).norm())
      centre = n;
  }
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
  CHECK_THROWS_WITH(RelaxationSolver(scene.solver),
                    Catch::Contains("0 < relaxation_omega < 2"));
}
