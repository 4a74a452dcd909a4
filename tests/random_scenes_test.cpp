// Random lattices in whole scenes: the lithostatic stress under gravity, and every
// criterion, reading, stepping method and contact, each run ending in equilibrium.
#include <catch2/catch.hpp>
#include <cmath>

#include "hard_case_checks.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/mechanics/node_stress.h"
#include "latfrac/solvers/equilibrium.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

TEST_CASE("Random lattice: lithostatic stress under gravity with the walls held",
          "[equilibrium][random]") {
  // Uniaxial strain: sigma_zz = -rho g depth, sigma_xx = nu / (1 - nu) sigma_zz. Each node
  // weighs rho g V_i, V_i its Voronoi cell, and the cells of the top nodes end at the top:
  // the surface is the top face itself. The node stresses scatter (their rms is about 9 %
  // of the mean at nu = 0.2, docs/model.md), so the check is on the mean over a band of
  // depths in the middle of the section, within 3 %.
  const int dim = GENERATE(2, 3);
  Scene scene = dim == 2 ? box_scene(2, 250.0, {30e3, 0, 15e3}, true)
                         : box_scene(3, 1000.0, {24e3, 12e3, 10e3}, true);
  scene.lattice.kind = LatticeKind::random;
  scene.lattice.seed = 4;
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  const Vector u = model.full_displacement(solver.affine_path().at(0.0), 0.0);
  const std::vector<double> stress = node_stresses(model, u);
  const Lattice& lattice = model.lattice;
  const double rho_g = scene.material.density * scene.gravity->g, nu = scene.material.poisson;
  double zz = 0, expected_zz = 0, xx = 0;
  int nodes = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3& p = lattice.positions[n];
    const bool band = p.z() > 0.3 * lattice.extent.z() && p.z() < 0.7 * lattice.extent.z() &&
                      std::abs(p.x() - lattice.extent.x() / 2) < 0.25 * lattice.extent.x() &&
                      (dim == 2 || std::abs(p.y() - lattice.extent.y() / 2) < 0.25 * lattice.extent.y());
    if (!band) continue;
    zz += stress[6 * n + 2];
    xx += stress[6 * n];
    expected_zz += -rho_g * (lattice.extent.z() - p.z());
    ++nodes;
  }
  INFO(dim << "-D, " << nodes << " nodes: mean sigma_zz / expected " << zz / expected_zz
           << ", mean sigma_xx / (nu / (1 - nu) sigma_zz) " << xx / (nu / (1 - nu) * zz));
  CHECK(nodes > 50);
  CHECK(zz / expected_zz == Approx(1).epsilon(0.03));
  CHECK(xx / (nu / (1 - nu) * zz) == Approx(1).epsilon(0.03));
  // The weight is the box's: the cells tile it.
  const Vector reactions = model.reactions(u);
  double base = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n)
    if (lattice.on_face(n, Face::z_min)) base += reactions[n * dim + dim - 1];
  double volume = lattice.extent.x() * lattice.extent.z() * (dim == 3 ? lattice.extent.y() : 1);
  CHECK(base == Approx(rho_g * volume).epsilon(1e-9));
}

namespace {

// A small random-lattice scene: `criterion` read through `reading`, with gravity, contact
// and a pre-cut, stretched to a few times the strength's strain.
Scene feature_scene(int dim, Criterion criterion, BondStress reading, SteppingMethod stepping) {
  Scene scene = dim == 2 ? box_scene(2, 1.0, {16.0, 0, 10.0}, true)
                         : box_scene(3, 1.0, {7.0, 5.0, 6.0}, true);
  scene.lattice.kind = LatticeKind::random;
  scene.lattice.seed = 100 + static_cast<int>(criterion);
  scene.strength = strength_of(criterion, 3e6, 30.0);
  scene.strength->tau0_factor = 2;
  scene.strength->bond_stress = reading;
  scene.contact = Contact{};
  scene.loading.total = 2e-4;
  scene.stepping = {stepping, 2e-5};
  const double top = scene.lattice.size[2];
  if (dim == 2) {
    scene.precuts.push_back({{8.2, 0, top + 0.5}, {8.2, 0, top - 3.0}, {}, {}, {}});
  } else {
    scene.precuts.push_back({{}, {}, {3.6, -0.5, top + 0.5}, {0, 6.0, 0}, {0, 0, -3.0}});
  }
  return scene;
}

}  // namespace

TEST_CASE("Random lattice: every criterion and reading, both steppings, with contact",
          "[fracture][random]") {
  // Gravity, walls, contact (a broken Delaunay bond keeps its contact spring), the four
  // criteria, the strain and both tensor readings (node stresses from the Voronoi cells),
  // event-driven and fixed steps: each run breaks bonds and ends in equilibrium, checked
  // on a freshly built model part by part.
  const int dim = GENERATE(2, 3);
  const SteppingMethod stepping = GENERATE(SteppingMethod::event, SteppingMethod::fixed);
  for (const auto& [criterion, reading] :
       {std::pair{Criterion::tensile, BondStress::strain},
        std::pair{Criterion::tensile, BondStress::critical_plane},
        std::pair{Criterion::tensile_or_shear, BondStress::tensor},
        std::pair{Criterion::elliptic, BondStress::strain},
        std::pair{Criterion::drucker_prager, BondStress::tensor}}) {
    const Scene scene = feature_scene(dim, criterion, reading, stepping);
    INFO(dim << "-D " << to_string(criterion) << ", reading " << to_string(reading)
             << (stepping == SteppingMethod::event ? ", event" : ", fixed"));
    RunResult result;
    REQUIRE_NOTHROW(result = run_scene(scene, quiet()));
    CHECK(snapshots_finite(result));
    int broken = 0, precut = 0;
    for (const BreakEvent& e : result.events) (e.mode == BreakMode::precut ? precut : broken)++;
    CHECK(precut > 0);
    CHECK(broken > 0);
    const FinalState state = final_state(scene, result);
    CHECK(balance(state).relative_residual <= 1e-9);
    int contacts = 0;
    for (std::int64_t b = 0; b < state.model.lattice.bond_count(); ++b)
      contacts += state.model.state(b) == PairState::closed;
    CHECK(contacts > 0);  // gravity presses some broken Delaunay bonds shut
  }
}

TEST_CASE("Random lattice: the complete model's mirror image breaks the mirror images of its bonds",
          "[random][friction][loading]") {
  // The scene reflected in x (lattice.mirror, the discontinuity at Lx - x_d) is the same
  // problem up to a rigid translation by the extension, which small kinematics does not
  // see: the same bonds break in the same order, at the same lambdas to rounding.
  // x_d off the centre, so that the scene is not its own mirror image.
  auto scene = [](bool mirror) {
    return read_problem_file(
        std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-2d.toml",
        {"lattice.spacing=2000", std::string("lattice.mirror=") + (mirror ? "true" : "false"),
         std::string("loading.basal_discontinuity=") + (mirror ? "35e3" : "25e3"),
         "output.snapshots=[0.04]"});
  };
  const RunResult plain = run_scene(scene(false), quiet());
  const RunResult mirrored = run_scene(scene(true), quiet());
  REQUIRE(plain.events.size() > 100);
  REQUIRE(mirrored.events.size() == plain.events.size());
  for (std::size_t k = 0; k < plain.events.size(); ++k) {
    INFO("event " << k);
    CHECK(mirrored.events[k].bond == plain.events[k].bond);
    CHECK(mirrored.events[k].mode == plain.events[k].mode);
    CHECK(mirrored.events[k].lambda == Approx(plain.events[k].lambda).epsilon(1e-9));
  }
  CHECK(mirrored.summary.contact_slip == Approx(plain.summary.contact_slip).epsilon(1e-6));
}
