// The basal velocity discontinuity ([loading] basal_discontinuity = x_d): the base left of
// x_d moves with the left wall, the rest with the right wall. Checked against the supports
// by hand, a mirror symmetry of the elastic solution, and the hand-computed first break.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "latfrac/mechanics/model.h"
#include "latfrac/mechanics/supports.h"
#include "latfrac/scene/run.h"
#include "latfrac/solvers/equilibrium.h"
#include "scenes.h"

using namespace latfrac;

namespace {

// 15 spacings long, so the base row (nodes at whole spacings) has no node at the centre.
Scene basal_scene(double x_d) {
  Scene scene = testing::box_scene(2, 1000.0, {15e3, 0, 6e3}, true);
  scene.loading.total = 1e-3;
  scene.loading.basal_discontinuity = x_d;
  return scene;
}

}  // namespace

TEST_CASE("basal discontinuity: the base's x follows the wall on its side", "[loading]") {
  const Scene scene = basal_scene(5250);
  const Model model = build_model(scene);
  const Lattice& lattice = model.lattice;
  const DofMap& dofs = model.dofs();
  const double half = lattice.extent.x() / 2;
  int left = 0, right = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3& p = lattice.positions[n];
    const bool base = lattice.on_face(n, Face::z_min);
    const bool wall = lattice.on_face(n, Face::x_min) || lattice.on_face(n, Face::x_max);
    const std::int64_t x = n * 2, z = n * 2 + 1;
    INFO("node " << n << " at " << p.x() << ", " << p.z());
    if (base) {
      REQUIRE(dofs.free_index[x] < 0);
      CHECK(dofs.free_index[z] < 0);  // the base's roller
      CHECK(dofs.prescribed_rate[x] == (p.x() < 5250 ? -half : half));
      (p.x() < 5250 ? left : right)++;
    } else if (!wall) {
      CHECK(dofs.free_index[x] >= 0);
      CHECK(dofs.free_index[z] >= 0);
    }
  }
  CHECK(left == 6);    // x = 0 .. 5000 m
  CHECK(right == 10);  // x = 6000 .. 15000 m
}

TEST_CASE("basal discontinuity at the centre: the elastic solution is mirror-antisymmetric",
          "[loading]") {
  // Mirror x -> L - x maps the lattice onto itself and the loading onto its negative in x:
  // u_x(L - x, z) = -u_x(x, z) and u_z(L - x, z) = u_z(x, z), gravity included.
  Scene scene = basal_scene(7500);
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  Vector free = Vector::Zero(model.dofs().free_count);
  solver.solve(1e-3, free);
  const Vector u = model.full_displacement(free, 1e-3);
  std::map<std::pair<long, long>, std::int64_t> node_at;
  const auto key = [](double x, double z) { return std::make_pair(std::lround(x), std::lround(z)); };
  for (std::int64_t n = 0; n < model.lattice.node_count(); ++n)
    node_at[key(model.lattice.positions[n].x(), model.lattice.positions[n].z())] = n;
  double largest = 0;
  for (std::int64_t n = 0; n < model.lattice.node_count(); ++n) largest = std::max(largest, std::abs(u[2 * n]));
  REQUIRE(largest > 0);
  for (std::int64_t n = 0; n < model.lattice.node_count(); ++n) {
    const Vec3& p = model.lattice.positions[n];
    const std::int64_t m = node_at.at(key(model.lattice.extent.x() - p.x(), p.z()));
    INFO("node " << n << " and its mirror " << m);
    CHECK(u[2 * m] == Approx(-u[2 * n]).margin(1e-9 * largest));
    CHECK(u[2 * m + 1] == Approx(u[2 * n + 1]).margin(1e-9 * largest));
  }
}

TEST_CASE("basal discontinuity: the base bond across x_d breaks first, at the hand value",
          "[loading]") {
  // No gravity, the tensile criterion on bond strains: the horizontal base bond across x_d
  // has its ends prescribed to -lambda L/2 and +lambda L/2, so its strain is lambda L / a
  // and it breaks at lambda* = sigma0 a / (E_b L), long before the far field (sigma0 / E).
  Scene scene = basal_scene(7500);
  scene.gravity.reset();
  scene.strength = testing::strength_of(Criterion::tensile, 50e6);
  scene.stepping = {SteppingMethod::event, 0};
  const Model model = build_model(scene);
  std::int64_t across = -1;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    const Bond& bond = model.lattice.bonds[b];
    const Vec3& p = model.lattice.positions[bond.i];
    const Vec3& q = model.lattice.positions[bond.j];
    if (p.z() == 0 && q.z() == 0 && std::min(p.x(), q.x()) < 7500 && std::max(p.x(), q.x()) > 7500)
      across = b;
  }
  REQUIRE(across >= 0);
  const double expected =
      50e6 * model.lattice.bond_length[across] / (model.bond_young[across] * model.lattice.extent.x());
  const RunResult result = run_scene(scene, {});
  REQUIRE(!result.events.empty());
  CHECK(result.events.front().bond == across);
  CHECK(result.events.front().lambda == Approx(expected).epsilon(1e-12));
}

TEST_CASE(
    "the tensile criterion needs no shear strength: without friction_angle or tau0 it "
    "runs, and breaks what it breaks with them",
    "[loading][criterion][input]") {
  // Tensile failure reads sigma0 alone (docs/criteria.md), so a [strength] of criterion and
  // sigma0 is complete; its bonds' tau0 is inf (none), which the builder's check of
  // overflowing strengths once refused.
  Scene scene = basal_scene(7500);
  scene.strength = testing::strength_of(Criterion::tensile, 50e6);
  scene.stepping = {SteppingMethod::event, 0};
  const RunResult with_angle = run_scene(scene, {});
  scene.strength->friction_angle.reset();
  const RunResult without = run_scene(scene, {});
  REQUIRE(!with_angle.events.empty());
  REQUIRE(without.events.size() == with_angle.events.size());
  for (std::size_t k = 0; k < without.events.size(); ++k) {
    CHECK(without.events[k].bond == with_angle.events[k].bond);
    CHECK(without.events[k].lambda == with_angle.events[k].lambda);
  }
}
