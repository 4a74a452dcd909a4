// The paper's crust under gravity with the walls held: uniaxial strain, so
// sigma_zz = -rho g depth and sigma_xx = nu / (1 - nu) sigma_zz. Also uniaxial extension
// without gravity: wall stress over strain is the plane-strain modulus E / (1 - nu^2).
#include <catch2/catch.hpp>

#include "latfrac/equilibrium.h"
#include "latfrac/node_stress.h"
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
  Vector free_u = Vector::Zero(s.model.dofs.free_count);
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
  const Lattice& lattice = s.model.lattice;
  const std::vector<double> stress = node_stresses(s.model, s.displacement);
  // The discrete body's free surface lies half a row pitch above the top row: each node
  // carries the weight of a row-pitch-thick slab.
  const double surface = lattice.extent.z() + lattice.row_pitch / 2;
  const double rho_g = scene.material.density * scene.gravity->g;
  const double nu = scene.material.poisson;
  int checked = 0;
  double worst_zz = 0, worst_xx = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3& p = lattice.positions[n];
    // Mid-body: away from the top and base rows, and more than the body's height from the
    // side faces, whose nodes have fewer bonds and shed weight into a boundary layer that
    // decays over about the height (docs/model.md).
    const bool mid_body =
        p.z() > 0.2 * lattice.extent.z() && p.z() < 0.8 * lattice.extent.z() &&
        std::abs(p.x() - lattice.extent.x() / 2) < 0.15 * lattice.extent.x() &&
        (dim == 2 || std::abs(p.y() - lattice.extent.y() / 2) < 0.15 * lattice.extent.y());
    if (!mid_body) continue;
    const double expected_zz = -rho_g * (surface - p.z());
    worst_zz = std::max(worst_zz, std::abs(stress[n * 6 + 2] / expected_zz - 1));
    worst_xx =
        std::max(worst_xx, std::abs(stress[n * 6 + 0] / (nu / (1 - nu) * stress[n * 6 + 2]) - 1));
    ++checked;
  }
  INFO("dim " << dim << ": " << checked << " nodes, worst zz " << worst_zz << ", worst xx "
              << worst_xx);
  CHECK(checked > 20);
  CHECK(worst_zz < 0.02);
  CHECK(worst_xx < 0.02);
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
