// Hard cases with contact and random scenes: chattering, pieces that slide on contacts,
// and random scenes of every kind, each final state checked for equilibrium part by part
// on a freshly built model (hard_case_checks.h).
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "hard_case_checks.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/scene/run.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

// A scene with contact across the given pre-cuts (x0, z0 -> x1, z1), no gravity, 12 x 8 m.
Scene contact_scene(Criterion criterion, double sigma0, double tau0_factor, double total,
                    const std::vector<std::array<double, 4>>& cuts) {
  Scene scene = testing::box_scene(2, 1.0, {12.0, 0, 8.0}, false);
  scene.strength = strength_of(criterion, sigma0);
  scene.strength->friction_angle = 30.0;
  scene.strength->tau0_factor = tau0_factor;
  scene.contact = Contact{};
  for (const auto& c : cuts)
    scene.precuts.push_back({{c[0], 0, c[1]}, {c[2], 0, c[3]}, {}, {}, {}});
  scene.loading.total = total;
  scene.stepping = {SteppingMethod::fixed, 1e-4};
  return scene;
}

// A contact scene pressed until it breaks around 4 to 6 triangular pieces cut out by
// pre-cuts. Each side overshoots its corners by 0.3 m, so the cuts cross and no bond
// keeps a piece attached at a corner.
Scene pressed_triangles(std::mt19937& random) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<double, 4>> cuts;
  const int triangles = 4 + static_cast<int>(3 * u(random));
  for (int t = 0; t < triangles; ++t) {
    const double x = 2 + 8 * u(random), z = 2 + 4 * u(random), radius = 1.5 + 1.5 * u(random),
                 turn = 2 * std::numbers::pi * u(random);
    for (int side = 0; side < 3; ++side) {
      const double a0 = turn + side * 2 * std::numbers::pi / 3, a1 = a0 + 2 * std::numbers::pi / 3;
      const double x0 = x + radius * std::cos(a0), z0 = z + radius * std::sin(a0),
                   x1 = x + radius * std::cos(a1), z1 = z + radius * std::sin(a1);
      const double e = 0.3 / std::hypot(x1 - x0, z1 - z0);
      cuts.push_back(
          {x0 - e * (x1 - x0), z0 - e * (z1 - z0), x1 + e * (x1 - x0), z1 + e * (z1 - z0)});
    }
  }
  const Criterion criterion = u(random) < 0.5 ? Criterion::elliptic : Criterion::tensile_or_shear;
  const double sigma0 = 1e6 * (0.5 + 5 * u(random)), factor = 1 + 3 * u(random);
  const double total = -1e-3 * (0.2 + 2 * u(random));
  return contact_scene(criterion, sigma0, factor, total, cuts);
}

}  // namespace

TEST_CASE("Hard: contact chattering is detected and resolved by the cycle rule", "[hard]") {
  // Whether a scene makes the active-set iteration revisit a set depends on rounding, so
  // the test takes the first of three lattices that cycles. The paper's Fig. 6 on a random
  // lattice with contact, at 2000 m (0.3 s a run), cycles on each of seeds 1, 2 and 3 (6,
  // 5 and 56 cycles resolved) with each of five OpenBLAS kernels (Haswell, SkylakeX, Zen,
  // Prescott, Nehalem; seed 2 with Nehalem 24), measured 2026-12-06. (The family of
  // pressed triangles this test used before cycled only through mechanisms that factor
  // updates left in the factor; checked after each update, none of its first 100 scenes
  // cycles: docs/robustness.md, "Mechanisms".)
  Scene scene;
  RunResult result;
  int seed = 1;
  for (; seed <= 3; ++seed) {
    scene = read_problem_file(std::string(LATFRAC_PROBLEMS_DIR) + "/fig6-elliptic-graben-random-2d.toml",
                              {"lattice.spacing=2000", "lattice.seed=" + std::to_string(seed),
                               "output.snapshots=[0.02, 0.04]"});
    result = run_scene(scene, quiet());
    if (result.summary.contact_cycles > 0) break;
  }
  INFO("seed " << seed);
  REQUIRE(result.summary.contact_cycles >= 1);
  CHECK(snapshots_finite(result));
  const RunResult again = run_scene(scene, quiet());
  check_same_events(result, again);
  CHECK(again.snapshots.back().displacement == result.snapshots.back().displacement);
}

TEST_CASE("Hard: random scenes with contact and crossing cuts all finish without NaN", "[hard]") {
  // Pieces held only by frictionless contacts can slide: the factorization's safety net
  // holds such nodes (docs/robustness.md). Every scene must finish with finite results.
  std::mt19937 random(20261122);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<std::array<double, 4>> cuts;
    const int count = 1 + static_cast<int>(3 * u(random));
    for (int c = 0; c < count; ++c) {
      const double x0 = 1 + 10 * u(random), z0 = 1 + 6 * u(random), angle = 3.14159 * u(random),
                   length = 2 + 6 * u(random);
      cuts.push_back({x0, z0, x0 + length * std::cos(angle),
                      std::clamp(z0 + length * std::sin(angle), -0.5, 8.5)});
    }
    const Criterion criterion = u(random) < 0.5 ? Criterion::elliptic : Criterion::tensile_or_shear;
    const double sigma0 = 1e6 * (0.5 + 5 * u(random)), factor = 1 + 3 * u(random);
    const double total = (u(random) < 0.5 ? -1 : 1) * 1e-3 * (0.2 + 2 * u(random));
    Scene scene = contact_scene(criterion, sigma0, factor, total, cuts);
    if (u(random) < 0.7) scene.gravity = Gravity{9.81};
    if (u(random) < 0.5) scene.stepping = {SteppingMethod::event, 0};
    INFO("trial " << trial);
    RunResult result;
    REQUIRE_NOTHROW(result = run_scene(scene, quiet()));
    CHECK(snapshots_finite(result));
  }
}



TEST_CASE("Hard: pieces cut out and pressed until they slide on contacts finish without NaN",
          "[hard]") {
  // Cut-out triangles pressed together come loose on frictionless contacts, so the updated
  // factor goes singular in a cascade of re-solves. Before residual checks saw NaN (Eigen's
  // maxCoeff can skip one), a NaN re-solve could pass, the node held at it, and the run
  // stop at the next solve: 1 to 6 of these 100 scenes did, depending on the BLAS kernel.
  std::mt19937 random(1105);
  for (int trial = 0; trial < 100; ++trial) {
    const Scene scene = pressed_triangles(random);
    INFO("scene " << trial);
    RunResult result;
    REQUIRE_NOTHROW(result = run_scene(scene, quiet()));
    CHECK(snapshots_finite(result));
  }
}
namespace {

// A random scene of any kind the problem files allow, 2-D or 3-D: any criterion and bond
// stress reading, extension or compression, event or fixed steps, pre-cuts, and each of
// gravity, contact, heterogeneity, a stiff or soft layer and large kinematics by chance.
Scene random_scene(int trial) {
  std::mt19937 random(7000 + trial);
  std::uniform_real_distribution<double> u(0, 1);
  const int dim = u(random) < 0.7 ? 2 : 3;
  const bool gravity = u(random) < 0.5;
  Scene scene = dim == 2 ? testing::box_scene(2, 1.0, {12.0, 0, 8.0}, gravity)
                         : testing::box_scene(3, 1.0, {6.0, 4.0, 5.0}, gravity);
  const auto criterion = static_cast<Criterion>(static_cast<int>(4 * u(random)));
  const double total = (u(random) < 0.6 ? 1 : -1) * 1e-3 * (0.2 + 3 * u(random));
  scene.loading.total = total;
  scene.strength = strength_of(criterion, 100e9 * std::abs(total) * (0.05 + u(random)));
  scene.strength->friction_angle = 20 + 25 * u(random);
  scene.strength->tau0_factor = 1 + 3 * u(random);
  if (criterion != Criterion::drucker_prager)
    scene.strength->bond_stress = static_cast<BondStress>(static_cast<int>(3 * u(random)));
  const int cuts = static_cast<int>(4 * u(random));
  for (int c = 0; c < cuts; ++c) {
    if (dim == 2) {
      const double x0 = 12 * u(random), z0 = 8 * u(random), x1 = 12 * u(random),
                   z1 = 8 * u(random);
      scene.precuts.push_back({{x0, 0, z0}, {x1, 0, z1}, {}, {}, {}});
    } else {
      const double x0 = 1 + 4 * u(random), z0 = 1 + 3 * u(random),
                   angle = std::numbers::pi * u(random);
      scene.precuts.push_back(
          {{}, {}, {x0, -0.5, z0}, {0, 5.0, 0}, {2 * std::cos(angle), 0, 2 * std::sin(angle)}});
    }
  }
  if (u(random) < 0.5) scene.contact = Contact{};
  if (u(random) < 0.3)
    scene.heterogeneity = Heterogeneity{0.8 * u(random), static_cast<std::uint64_t>(trial)};
  if (u(random) < 0.2) {
    Layer layer;
    layer.z_min = 2 + 2 * u(random);
    layer.z_max = layer.z_min + 1 + 2 * u(random);
    layer.material = scene.material;
    layer.material.young *= std::pow(10.0, 4 * u(random) - 2);
    scene.layers.push_back(layer);
  }
  scene.large_kinematics = u(random) < 0.15;
  if (u(random) < 0.5)
    scene.stepping = {SteppingMethod::event, 0};
  else
    scene.stepping = {SteppingMethod::fixed, std::abs(total) / (1 + 50 * u(random))};
  return scene;
}

// random_scene(trial) with contact always on, 3 to 7 more cuts, and by chance a fixed
// base, a fixed left wall or a roller on top.
Scene random_contact_scene(int trial) {
  Scene scene = random_scene(trial);
  std::mt19937 random(99000 + trial);
  std::uniform_real_distribution<double> u(0, 1);
  scene.contact = Contact{};
  const int extra = 3 + static_cast<int>(5 * u(random));
  for (int c = 0; c < extra; ++c) {
    const double x0 = (scene.lattice.dim == 2 ? 12 : 4) * u(random) + (scene.lattice.dim == 2 ? 0 : 1),
                 z0 = (scene.lattice.dim == 2 ? 8 : 3) * u(random) + (scene.lattice.dim == 2 ? 0 : 1),
                 angle = std::numbers::pi * u(random), length = 1 + 5 * u(random);
    if (scene.lattice.dim == 2) {
      scene.precuts.push_back({{x0, 0, z0},
                               {x0 + length * std::cos(angle), 0, z0 + length * std::sin(angle)},
                               {}, {}, {}});
    } else {
      scene.precuts.push_back(
          {{}, {}, {x0, -0.5, z0}, {0, 5.0, 0}, {2 * std::cos(angle), 0, 2 * std::sin(angle)}});
    }
  }
  if (u(random) < 0.3) scene.faces[static_cast<int>(Face::z_min)] = FaceCondition::fixed;
  if (u(random) < 0.3) scene.faces[static_cast<int>(Face::x_min)] = FaceCondition::fixed;
  if (u(random) < 0.3) scene.faces[static_cast<int>(Face::z_max)] = FaceCondition::roller;
  return scene;
}

// Runs scenes first .. last - 1 of a family; each must finish, finite, with every free dof
// of a supported part in equilibrium to 1e-9 of the load.
void check_scenes_in_equilibrium(Scene (*family)(int), int first, int last) {
  for (int trial = first; trial < last; ++trial) {
    const Scene scene = family(trial);
    INFO("trial " << trial);
    RunResult result;
    REQUIRE_NOTHROW(result = run_scene(scene, quiet()));
    CHECK(snapshots_finite(result));
    CHECK(balance(final_state(scene, result)).relative_residual <= 1e-9);
  }
}

}  // namespace

TEST_CASE("Hard: 130 random scenes of every kind end in equilibrium, part by part", "[hard]") {
  // Found by this search, fixed in docs/model.md and docs/robustness.md: event-driven
  // contact left contacts tied with a switch penetrating for the rest of the path (trials
  // 13, 15, 18, 60, 75: residuals up to 0.2 of the load); the large-kinematics route did
  // not settle contacts at the end (86); and the singular-stiffness safety net held a
  // node along an axis in which its part was supported, so the walls pushed against the
  // hold (126: 0.17 of the load). 600 scenes pass with three BLAS kernels.
  check_scenes_in_equilibrium(random_scene, 0, 130);
}

TEST_CASE("Hard: 60 random scenes with contact and many cuts end in equilibrium", "[hard]") {
  // Found by this search (scenes 75 and 119): at lambda = 0 without gravity every contact
  // sits at dn = 0, and contacts whose rate was rounding (either sign) switched back and
  // forth at one lambda until the cycle guard stopped switching there, leaving others
  // penetrating for the rest of the path (0.26 and 0.002 of the load). 800 scenes pass.
  check_scenes_in_equilibrium(random_contact_scene, 70, 130);
}
