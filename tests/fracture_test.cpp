// Breaking bonds: factor updates against fresh factorizations, the first break at its
// analytic load, contact across a pre-cut, and a block cut loose.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <set>

#include "final_state.h"
#include "latfrac/solvers/equilibrium.h"
#include "latfrac/mechanics/fragments.h"
#include "latfrac/scene/run.h"
#include "random_breaks.h"
#include "scenes.h"

using namespace latfrac;

namespace {

using testing::final_state;
using testing::FinalState;

Scene fracture_scene(Criterion criterion, double sigma0) {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, false);
  scene.strength = testing::strength_of(criterion, sigma0);
  scene.stepping = {SteppingMethod::fixed, 1e-3};
  return scene;
}

double relative_difference(const Vector& a, const Vector& b) {
  return max_abs(a - b) / max_abs(b);
}

double wall_reaction(const FinalState& state, Face face) {
  const Vector reactions = state.model.reactions(state.displacement);
  double force = 0;
  for (std::int64_t n = 0; n < state.model.lattice.node_count(); ++n) {
    if (state.model.lattice.on_face(n, face)) force += reactions[n * state.model.dim()];
  }
  return force;
}

}  // namespace

TEST_CASE("After 100 random breaks the updated factor solves like a fresh factorization",
          "[fracture][solver]") {
  const int dim = GENERATE(2, 3);
  const Scene scene = dim == 2 ? testing::box_scene(2, 1.0, {40.0, 0, 20.0}, true)
                               : testing::box_scene(3, 1.0, {10.0, 8.0, 8.0}, true);
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  solver.affine_path();
  testing::break_random_bonds(model, solver, 100, 42);
  CHECK(solver.counters().factor_updates == 100);
  CHECK(solver.counters().factorizations == 1);
  const AffinePath updated = solver.affine_path();
  EquilibriumSolver fresh(model, scene.solver);
  const AffinePath reference = fresh.affine_path();
  CHECK(relative_difference(updated.gravity, reference.gravity) < 1e-10);
  CHECK(relative_difference(updated.extension, reference.extension) < 1e-10);
}

TEST_CASE("Re-solves at one lambda after breaks and contact switches match a fresh solve",
          "[fracture][solver]") {
  // A cascade's re-solve is the last solution plus K^-1 (the forces of the changed
  // springs), a right-hand side with a few entries. Walls, base and gravity make the
  // changed springs include boundary bonds (prescribed displacements) and loaded ones.
  const int dim = GENERATE(2, 3);
  Scene scene = dim == 2 ? testing::box_scene(2, 1.0, {40.0, 0, 20.0}, true)
                         : testing::box_scene(3, 1.0, {10.0, 8.0, 8.0}, true);
  scene.contact = Contact{};
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  const double lambda = 2e-3;
  Vector u = solver.checked_solve(lambda);
  int closed = 0;
  testing::for_random_supported_breaks(model, 60, 5, [&](std::int64_t bond) {
    // Every third broken bond that can carry contact closes it (a rank-1 update up).
    const bool closes = model.can_touch(bond) && closed++ % 3 == 0;
    solver.set_pair_state(bond, closes ? PairState::closed : PairState::open);
    u = solver.checked_solve(lambda);
  });
  CHECK(closed > 6);  // contacts did close along the way
  CHECK(solver.counters().factorizations == 1);
  CHECK(solver.counters().correction_solves == 60);
  EquilibriumSolver fresh(model, scene.solver);
  const Vector reference = fresh.checked_solve(lambda);
  CHECK(fresh.counters().correction_solves == 0);
  CHECK(relative_difference(u, reference) < 1e-10);
}

TEST_CASE("After solver.refactor_every updates the next break refactorizes", "[fracture][solver]") {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, true);
  scene.solver.refactor_every = 10;
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  solver.checked_solve(1e-3);
  int breaks = 0;
  testing::for_random_supported_breaks(model, 35, 7, [&](std::int64_t bond) {
    solver.set_pair_state(bond, PairState::open);
    solver.checked_solve(1e-3);
    ++breaks;
  });
  // Breaks 1-10 update the factor; the 11th finds 10 updates and refactorizes instead;
  // 12-21 update; 22 refactorizes; 23-32 update; 33 refactorizes; 34 and 35 update.
  CHECK(breaks == 35);
  CHECK(solver.counters().factorizations == 4);
  CHECK(solver.counters().factor_updates == 32);
  EquilibriumSolver fresh(model, scene.solver);
  CHECK(relative_difference(solver.checked_solve(1e-3), fresh.checked_solve(1e-3)) < 1e-10);
}

TEST_CASE("The first bond breaks at the first step past its analytic load", "[fracture]") {
  // Rollers on top and base and extension walls: the exact state is u_x = lambda (x - c),
  // u_z = 0, so every horizontal bond has sigma_n = E lambda and the tensile criterion
  // first fails at lambda* = sigma0 / E = 5e-4.
  Scene scene = fracture_scene(Criterion::tensile, 50e6);
  scene.faces[static_cast<int>(Face::z_max)] = FaceCondition::roller;
  scene.loading.total = 1e-3;
  scene.stepping.increment = 1.5e-4;  // steps 0, 1.5e-4, ... 4.5e-4, 6e-4: the break at 6e-4
  const RunResult result = run_scene(scene, {});
  REQUIRE(!result.events.empty());
  const BreakEvent& first = result.events.front();
  CHECK(first.lambda == Approx(6e-4).epsilon(1e-12));
  CHECK(first.failure_index == Approx(100e9 * 6e-4 / 50e6).epsilon(1e-9));
  CHECK(first.mode == BreakMode::tensile);
  CHECK(result.summary.breaks == static_cast<std::int64_t>(result.events.size()));
}

TEST_CASE("On an affine scene a fixed step without a break needs no solve", "[fracture]") {
  // Equilibrium is u_g + lambda u_e (docs/model.md): one two-column solve gives every step.
  Scene scene = fracture_scene(Criterion::elliptic, 1e30);  // nothing breaks
  scene.gravity = Gravity{9.81};
  scene.loading.total = 0.04;
  for (double increment : {1e-3, 1e-4}) {
    scene.stepping.increment = increment;
    const RunResult result = run_scene(scene, {});
    INFO("ds " << increment);
    CHECK(result.summary.breaks == 0);
    CHECK(result.summary.solves == 1);
    CHECK(result.summary.factorizations == 1);
  }
  // With breaks: a re-solve per break, a new path at the step after a cascade, and a
  // solve after each fresh factorization (a part held); the other steps still cost none.
  scene.strength = testing::strength_of(Criterion::tensile, 50e6);
  scene.stepping.increment = 1e-4;
  const RunResult broken = run_scene(scene, {});
  REQUIRE(broken.summary.breaks > 0);
  std::set<double> cascades;
  for (const BreakEvent& event : broken.events) cascades.insert(event.lambda);
  INFO(broken.summary.breaks << " breaks at " << cascades.size() << " steps of 400");
  CHECK(broken.summary.solves <= 1 + broken.summary.breaks + std::ssize(cascades) +
                                     broken.summary.factorizations);
}

TEST_CASE("Contact across a pre-cut transmits the load when pressed and none when pulled",
          "[fracture][contact]") {
  Scene scene = fracture_scene(Criterion::tensile, 1e30);  // nothing breaks
  scene.precuts.push_back({{10.25, 0, -1.0}, {10.25, 0, 11.0}, {}, {}, {}});
  scene.contact = Contact{};
  SECTION("pressed: the walls' force passes through the closed contacts") {
    scene.loading.total = -1e-3;
    scene.stepping.increment = 1e-3;
    const RunResult result = run_scene(scene, {});
    const FinalState state = final_state(scene, result);
    const double right = wall_reaction(state, Face::x_max),
                 left = wall_reaction(state, Face::x_min);
    // The force carried across the cut: the x components of the contact springs' forces
    // on the right-hand block (each bond oriented from the left block to the right one).
    double through_cut = 0;
    int active = 0;
    for (std::int64_t b = 0; b < state.model.lattice.bond_count(); ++b) {
      if (state.model.state(b) != PairState::closed) continue;
      ++active;
      const Vec3& n0 = state.model.lattice.bond_direction[b];
      const double tension = state.model.normal_stiffness[b] *
                             n0.dot(state.model.bond_displacement(state.displacement, b));
      const bool j_on_right =
          state.model.lattice.positions[state.model.lattice.bonds[b].j].x() > 10.25;
      through_cut += (j_on_right ? -1.0 : 1.0) * tension * n0.x();
    }
    CHECK(active > 0);
    CHECK(right < 0);  // the wall pushes inward
    CHECK(left == Approx(-right).epsilon(1e-9));
    CHECK(through_cut == Approx(-right).epsilon(1e-9));  // the right block: wall + cut = 0
    // Equilibrium with the sign conditions: no open contact penetrates.
    for (std::int64_t b = 0; b < state.model.lattice.bond_count(); ++b) {
      if (state.model.state(b) != PairState::open || !state.model.contact_capable(b)) continue;
      CHECK(state.model.lattice.bond_direction[b].dot(
                state.model.bond_displacement(state.displacement, b)) >= -1e-12);
    }
  }
  SECTION("pulled: the blocks separate and the walls feel nothing") {
    scene.loading.total = 1e-3;
    scene.stepping.increment = 1e-3;
    const RunResult result = run_scene(scene, {});
    const FinalState state = final_state(scene, result);
    int active = 0;
    for (std::int64_t b = 0; b < state.model.lattice.bond_count(); ++b)
      active += state.model.state(b) == PairState::closed;
    CHECK(active == 0);
    // Scale: the force the intact body would carry, E' lambda H.
    const double scale = 100e9 / 0.96 * 1e-3 * 10.0;
    CHECK(std::abs(wall_reaction(state, Face::x_max)) < 1e-9 * scale);
  }
}

TEST_CASE("A block cut loose is held (no contact) or rests on its contacts, never NaN",
          "[fracture][contact]") {
  // A horizontal pre-cut across the whole width at mid-height: without contact the upper
  // block has no vertical support.
  Scene scene = fracture_scene(Criterion::elliptic, 1e30);
  scene.gravity = Gravity{9.81};
  scene.precuts.push_back({{-1.0, 0, 5.2}, {21.0, 0, 5.2}, {}, {}, {}});
  scene.loading.total = 1e-3;
  scene.stepping.increment = 5e-4;
  const bool contact = GENERATE(false, true);
  if (contact) scene.contact = Contact{};
  const RunResult result = run_scene(scene, {});
  const Snapshot& last = result.snapshots.back();
  for (double value : last.displacement) REQUIRE(std::isfinite(value));
  for (double value : last.node_stress) REQUIRE(std::isfinite(value));
  const FinalState state = final_state(scene, result);
  const double weight = state.model.external_force.sum();  // negative: downward
  if (!contact) {
    // Held vertically where it was (the walls still hold it along x), and reported.
    CHECK(result.fragments.size() == 1);
    for (std::int64_t n = 0; n < state.model.lattice.node_count(); ++n) {
      if (state.model.lattice.positions[n].z() > 5.2)
        CHECK(state.model.node_displacement(state.displacement, n).z() == 0.0);
    }
  } else {
    // Resting on its contacts: the base carries the whole weight.
    const Vector reactions = state.model.reactions(state.displacement);
    double base = 0;
    for (std::int64_t n = 0; n < state.model.lattice.node_count(); ++n) {
      if (state.model.lattice.on_face(n, Face::z_min)) base += reactions[n * 2 + 1];
    }
    CHECK(result.fragments.empty());
    CHECK(base == Approx(-weight).epsilon(1e-9));
  }
}
