// Event-driven breaking: exact first breaks, independence from stepping parameters,
// convergence of the fixed-step method to it, mirror symmetry and determinism.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>

#include "latfrac/fracture/break_source.h"
#include "latfrac/fracture/fracture_run.h"
#include "latfrac/fracture/initial_supports.h"
#include "latfrac/mechanics/model.h"
#include "latfrac/scene/run.h"
#include "scenes.h"

using namespace latfrac;

namespace {

Scene strip_scene(Criterion criterion) {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, false);
  scene.strength = testing::strength_of(criterion, 50e6);
  scene.stepping = {SteppingMethod::event, 0};
  return scene;
}

// A small crust: gravity, a pre-cut from the surface, the tensile criterion.
Scene notched_scene() {
  Scene scene = testing::box_scene(2, 1000.0, {16e3, 0, 8e3}, true);
  scene.strength = testing::strength_of(Criterion::tensile, 50e6);
  scene.precuts.push_back({{8250, 0, 9000}, {8250, 0, 5500}, {}, {}, {}});
  scene.loading.total = 5e-4;
  scene.stepping = {SteppingMethod::event, 0};
  return scene;
}

std::set<std::int64_t> broken_set(const RunResult& result) {
  std::set<std::int64_t> broken;
  for (const BreakEvent& e : result.events) {
    if (e.mode != BreakMode::precut) broken.insert(e.bond);
  }
  return broken;
}

double symmetric_difference(const std::set<std::int64_t>& a, const std::set<std::int64_t>& b) {
  std::size_t differ = 0;
  for (auto x : a) differ += !b.count(x);
  for (auto x : b) differ += !a.count(x);
  return b.empty() ? static_cast<double>(differ) : static_cast<double>(differ) / b.size();
}

}  // namespace

TEST_CASE("Event-driven breaking finds the analytic first break to 1e-12", "[continuation]") {
  // Rollers on top and base: every horizontal bond has sigma_n = E lambda exactly, so the
  // tensile criterion first fails at lambda* = sigma0 / E = 5e-4.
  Scene scene = strip_scene(Criterion::tensile);
  scene.faces[static_cast<int>(Face::z_max)] = FaceCondition::roller;
  scene.loading.total = 1e-3;
  const RunResult event = run_scene(scene, {});
  REQUIRE(!event.events.empty());
  CHECK(event.events.front().lambda == Approx(5e-4).epsilon(1e-12));
  CHECK(event.events.front().failure_index == Approx(1.0).epsilon(1e-12));
  // The fixed-step method finds it within one increment.
  const double ds = 1.7e-4;
  scene.stepping = {SteppingMethod::fixed, ds};
  const RunResult fixed = run_scene(scene, {});
  REQUIRE(!fixed.events.empty());
  CHECK(fixed.events.front().lambda >= 5e-4);
  CHECK(fixed.events.front().lambda < 5e-4 + ds);
}

TEST_CASE("With the stress tensor the first tensile break is at sigma0 / M", "[continuation]") {
  // Rollers on top and base hold eps_zz = 0: uniaxial strain eps_xx = lambda, so the
  // interior stress is sigma_xx = M lambda with the P-wave modulus
  // M = E (1 - nu) / ((1 + nu)(1 - 2 nu)), and a horizontal bond's resolved sigma_n is
  // sigma_xx. Its own strain would give E lambda instead (the previous test). sigma_xx is
  // also the largest principal stress (sigma_zz = M lambda nu / (1 - nu) is smaller), so
  // the critical-plane reading breaks at the same lambda.
  Scene scene = strip_scene(Criterion::tensile);
  scene.strength->bond_stress = GENERATE(BondStress::tensor, BondStress::critical_plane);
  scene.faces[static_cast<int>(Face::z_max)] = FaceCondition::roller;
  scene.loading.total = 1e-3;
  const RunResult event = run_scene(scene, {});
  REQUIRE(!event.events.empty());
  const double E = scene.material.young, nu = scene.material.poisson;
  const double M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  CHECK(event.events.front().lambda == Approx(scene.strength->sigma0 / M).epsilon(1e-9));
  CHECK(event.events.front().failure_index == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("With the critical-plane reading tensile_or_shear fails in shear at 2 tau0 / E'",
          "[continuation]") {
  // A free top and no gravity: plane-strain uniaxial stress sigma_xx = E' lambda with
  // E' = E / (1 - nu^2), sigma_zz = 0, so the largest shear is r = E' lambda / 2 on the 45
  // degree planes. With tau0 = 10 MPa the shear part reaches 1 at 2 tau0 / E', before
  // E' lambda reaches sigma0.
  Scene scene = strip_scene(Criterion::tensile_or_shear);
  scene.strength->tau0 = 10e6;
  scene.strength->bond_stress = BondStress::critical_plane;
  scene.loading.total = 1e-3;
  const RunResult event = run_scene(scene, {});
  REQUIRE(!event.events.empty());
  const double nu = scene.material.poisson;
  const double plane_strain_modulus = scene.material.young / (1 - nu * nu);
  CHECK(event.events.front().lambda == Approx(2 * 10e6 / plane_strain_modulus).epsilon(1e-9));
  CHECK(event.events.front().mode == BreakMode::shear);
}

TEST_CASE("The event-driven result depends on no stepping parameter", "[continuation]") {
  Scene scene = notched_scene();
  const RunResult reference = run_scene(scene, {});
  REQUIRE(broken_set(reference).size() > 3);
  scene.stepping.increment = 1e-3;  // ignored by the event-driven method
  scene.output.snapshots = {1e-4, 2.5e-4, 5e-4};
  const RunResult other = run_scene(scene, {});
  REQUIRE(other.events.size() == reference.events.size());
  for (std::size_t k = 0; k < reference.events.size(); ++k) {
    CHECK(other.events[k].bond == reference.events[k].bond);
    CHECK(other.events[k].lambda == reference.events[k].lambda);
  }
}

TEST_CASE("Fixed-step runs converge to the event-driven result as ds shrinks", "[continuation]") {
  Scene scene = notched_scene();
  // Both ways of taking a bond's stress: its own strain, and the resolved stress tensor.
  scene.strength->bond_stress =
      GENERATE(BondStress::strain, BondStress::tensor, BondStress::critical_plane);
  const std::set<std::int64_t> reference = broken_set(run_scene(scene, {}));
  std::vector<double> differences;
  for (double ds : {1e-4, 1e-5, 1e-6}) {
    scene.stepping = {SteppingMethod::fixed, ds};
    differences.push_back(symmetric_difference(broken_set(run_scene(scene, {})), reference));
  }
  INFO("broken-set differences at ds = 1e-4, 1e-5, 1e-6: "
       << differences[0] << ", " << differences[1] << ", " << differences[2]);
  CHECK(differences[2] <= differences[0]);
  CHECK(differences[2] == 0.0);
}

TEST_CASE("A mirror-symmetric scene breaks mirror pairs at equal lambda, the same on every run",
          "[continuation]") {
  Scene scene = testing::box_scene(2, 1000.0, {16e3, 0, 8e3}, true);
  scene.strength = testing::strength_of(Criterion::elliptic, 50e6, 34.0);
  scene.strength->tau0_factor = 3.0;
  scene.loading.total = 2e-3;
  scene.stepping = {SteppingMethod::event, 0};
  const RunResult result = run_scene(scene, {});
  const Model model = build_model(scene);
  // The mirror image of each bond about x = L / 2.
  std::map<std::pair<long, long>, std::int64_t> node_at;
  auto key = [](const Vec3& p) {
    return std::make_pair(std::lround(p.x() * 8), std::lround(p.z() * 8));
  };
  for (std::int64_t n = 0; n < model.lattice.node_count(); ++n)
    node_at[key(model.lattice.positions[n])] = n;
  std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> bond_of;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    bond_of[{model.lattice.bonds[b].i, model.lattice.bonds[b].j}] = b;
  }
  auto mirror = [&](std::int64_t b) {
    auto image = [&](std::int64_t n) {
      Vec3 p = model.lattice.positions[n];
      p.x() = model.lattice.extent.x() - p.x();
      return node_at.at(key(p));
    };
    const std::int64_t i = image(model.lattice.bonds[b].i), j = image(model.lattice.bonds[b].j);
    return bond_of.at({std::min(i, j), std::max(i, j)});
  };
  std::map<std::int64_t, double> broken_at;
  for (const BreakEvent& e : result.events) broken_at[e.bond] = e.lambda;
  REQUIRE(broken_at.size() >= 2);
  for (const auto& [bond, lambda] : broken_at) {
    const std::int64_t partner = mirror(bond);
    INFO("bond " << bond << " (lambda " << lambda << "), mirror " << partner);
    REQUIRE(broken_at.count(partner));
    CHECK(std::abs(broken_at.at(partner) - lambda) <= 1e-9 * std::max(std::abs(lambda), 1e-12));
  }
  // Determinism: the same events, bit for bit, on a second run.
  const RunResult again = run_scene(scene, {});
  REQUIRE(again.events.size() == result.events.size());
  for (std::size_t k = 0; k < result.events.size(); ++k) {
    CHECK(again.events[k].bond == result.events[k].bond);
    CHECK(again.events[k].lambda == result.events[k].lambda);
  }
}

TEST_CASE("On an affine scene the CVODE route and the closed-form route agree", "[continuation]") {
  const Scene scene = notched_scene();
  const RunResult closed_form = run_scene(scene, {});
  // The same scene through the general route: CVODE with root finding, KINSOL corrections.
  Model model = build_model(scene);
  const RunResult integrated = testing::run_model(model, scene, /*integrated=*/true);
  REQUIRE(closed_form.events.size() > 3);
  REQUIRE(integrated.events.size() == closed_form.events.size());
  for (std::size_t k = 0; k < closed_form.events.size(); ++k) {
    INFO("event " << k);
    CHECK(integrated.events[k].bond == closed_form.events[k].bond);
    CHECK(integrated.events[k].lambda ==
          Approx(closed_form.events[k].lambda).epsilon(1e-8).margin(1e-300));
  }
}

TEST_CASE("Large kinematics agrees with small kinematics at small strain", "[continuation]") {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, false);
  scene.loading.total = 1e-5;
  const RunResult small = run_scene(scene, {});
  scene.large_kinematics = true;
  const RunResult large = run_scene(scene, {});
  const auto& a = small.snapshots.back().displacement;
  const auto& b = large.snapshots.back().displacement;
  double difference = 0, scale = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    difference = std::max(difference, std::abs(a[k] - b[k]));
    scale = std::max(scale, std::abs(a[k]));
  }
  // The two laws differ at second order in the strain (1e-5 here).
  CHECK(difference / scale < 1e-3);
  CHECK(difference > 0);
}

TEST_CASE("the cascade's screen passes every bond the exact check finds at f >= 1",
          "[event][screen]") {
  // FailureEvaluator::may_fail_at reads f on the path's stresses, which differ from the
  // state's by rounding: wherever critical_group finds a bond at f >= 1, the screen must
  // say so (or the cascade would end early); well below the first crossing it must not
  // (on the stress readings).
  const BondStress reading =
      GENERATE(BondStress::tensor, BondStress::critical_plane, BondStress::strain);
  // Without gravity nothing is near failure at lambda = 0; extension brings the first
  // bond to f = 1 at lc.
  Scene scene = testing::box_scene(2, 1000.0, {16e3, 0, 8e3}, false);
  scene.strength = testing::strength_of(Criterion::elliptic, 50e6);
  scene.strength->bond_stress = reading;
  Model model = build_model(scene);
  prepare_supports(model, scene.source_path);
  EquilibriumSolver solver(model, scene.solver);
  const FailureEvaluator evaluator(*scene.strength, model);
  const AffinePath path = solver.affine_path();
  const FullPath full = full_path(model, path);
  const PathStresses stresses = evaluator.path_stresses(model, full.at_zero, full.per_lambda, 1.0);
  const PathCrossing first = next_break(model, evaluator, stresses, 0.0, 0.01);
  REQUIRE(first.found());
  const double lc = first.lambda;
  REQUIRE(lc > 0);
  // (On the strain reading the screen always passes: its exact check has no sweep to save.)
  CHECK(evaluator.may_fail_at(model, stresses, 0.99 * lc) == (reading == BondStress::strain));
  CHECK(evaluator.critical_group(model, model.full_displacement(path.at(0.99 * lc), 0.99 * lc), 1.0)
            .empty());
  int exact_found = 0;
  for (int k = -20; k <= 20; ++k) {
    const double lambda = lc * (1 + k * 1e-13);
    const Vector u = model.full_displacement(path.at(lambda), lambda);
    const bool exact = !evaluator.critical_group(model, u, 1.0).empty();
    exact_found += exact;
    if (exact) CHECK(evaluator.may_fail_at(model, stresses, lambda));
  }
  CHECK(exact_found > 0);  // the exact check did find the bond on this side of the crossing
  CHECK(evaluator.may_fail_at(model, stresses, 1.01 * lc));
}
