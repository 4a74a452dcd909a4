// The paper's crust under gravity with the walls held: uniaxial strain, so
// sigma_zz = -rho g depth and sigma_xx = nu / (1 - nu) sigma_zz. Also uniaxial extension
// without gravity: wall stress over strain is the plane-strain modulus E / (1 - nu^2).
#include <catch2/catch.hpp>

#include "latfrac/solvers/equilibrium.h"
#include "latfrac/mechanics/node_stress.h"
#include "lithostatic_check.h"
#include "scenes.h"

using namespace latfrac;

namespace {

struct Solved {
  Model model;
  Vector displacement;
};

Solved solve_scene(const Scene& scene, double lambda) {
  Solved s{build_model(scene), {}};
  EquilibriumSolver solver(s.model, scene.solver);
  Vector free_u = Vector::Zero(s.model.dofs().free_count);
  solver.solve(lambda, free_u);
  s.displacement = s.model.full_displacement(free_u, lambda);
  return s;
}

}  // namespace

TEST_CASE("Lithostatic stress under gravity with the walls held", "[equilibrium]") {
  const int dim = GENERATE(2, 3);
  const Scene scene = dim == 2 ? testing::box_scene(2, 500.0, {30e3, 0, 15e3}, true)
                               : testing::box_scene(3, 1000.0, {30e3, 30e3, 8e3}, true);
  const Solved s = solve_scene(scene, 0.0);
  const testing::LithostaticError error = testing::lithostatic_error(scene, s.model, s.displacement);
  INFO("dim " << dim << ": " << error.checked << " nodes, worst zz " << error.zz << ", worst xx "
              << error.xx);
  CHECK(error.checked > 20);
  CHECK(error.zz < 0.02);
  CHECK(error.xx < 0.02);
}

namespace {

// Wall reaction over the body's cross-section (its volume N V0 over its length), over the
// strain lambda.
double apparent_modulus(const Scene& scene, double lambda) {
  const Solved s = solve_scene(scene, lambda);
  const Lattice& lattice = s.model.lattice;
  const Vector reactions = s.model.reactions(s.displacement);
  double wall_force = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    if (lattice.on_face(n, Face::x_max)) wall_force += reactions[n * lattice.dim];
  }
  const double area = lattice.node_count() * lattice.node_volume / lattice.extent.x();
  return wall_force / area / lambda;
}

}  // namespace

TEST_CASE("Uniaxial extension: wall stress over strain is the plane-strain modulus",
          "[equilibrium]") {
  const Material material = testing::paper_material();
  const double expected = material.young / (1 - material.poisson * material.poisson);
  SECTION("2-D, 100 x 20 spacings") {
    const double modulus =
        apparent_modulus(testing::box_scene(2, 1.0, {100.0, 0, 20.0}, false), 1e-3);
    CHECK(modulus == Approx(expected).epsilon(0.02));
  }
  SECTION("3-D: the modulus of cubes of side 10 a and 20 a, extrapolated in a / L") {
    // Surface nodes lack bonds, so a body of side L is softer by O(a / L); the continuum
    // limit M(inf) = 2 M(2L) - M(L) removes that first-order term.
    const double small =
        apparent_modulus(testing::box_scene(3, 1.0, {10.0, 10.0, 10.0}, false), 1e-3);
    const double large =
        apparent_modulus(testing::box_scene(3, 1.0, {20.0, 20.0, 20.0}, false), 1e-3);
    INFO("M(10 a) " << small << ", M(20 a) " << large);
    CHECK(small < large);
    CHECK(2 * large - small == Approx(expected).epsilon(0.02));
  }
}
