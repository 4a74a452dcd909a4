// Hard cases of near-mechanisms (docs/robustness.md, "Mechanisms"): nu = 1/4, where the
// shear springs vanish and breaking leaves pieces that turn about a node, and massive
// breaking under strong gravity. Each run must finish, finite, with every dof that the run
// did not hold in equilibrium, checked on a freshly built model; and a random search over
// the parameters that showed these cases must meet no ill-conditioned ending.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "final_state.h"
#include "hard_case_checks.h"
#include "latfrac/fracture/fracture_run.h"
#include "latfrac/fracture/initial_supports.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/mechanics/stiffness.h"
#include "latfrac/scene/model_builder.h"
#include "latfrac/solvers/equilibrium.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

// run_scene's steps, keeping the run's model: its supports show every dof the run held.
struct KeptRun {
  Model model;
  RunResult result;
};

KeptRun run_keeping_model(const Scene& scene) {
  const std::shared_ptr<const FailureCriterion> criterion =
      make_criterion(*scene.strength, scene.lattice.dim);
  KeptRun run{build_model(scene, criterion.get()), {}};
  run.result.fragments = prepare_supports(run.model, scene.source_path);
  EquilibriumSolver solver(run.model, scene.solver);
  ProgressLine progress(false);
  FractureRun fracture(run.model, criterion, scene.strength->bond_stress, schedule_of(scene),
                       scene.solver, solver, progress, run.result);
  fracture.run();
  static_cast<RunCounters&>(run.result.summary) = fracture.counters();
  return run;
}

// The final state on a fresh model, dof by dof. A dof prescribed there is a support; a dof
// free there but prescribed in the run's model was held by the run; every other dof must
// carry no net force. Parts are found here through the intact bonds: a held dof whose part
// is supported along its axis was held for a mechanism, not for a missing support.
struct HeldBalance {
  double relative_residual = 0;  // max |R| over dofs not held / max |R(0, lambda)|
  double support_reaction = 0;   // vertical, N
  double holding_force = 0;      // vertical, N
  double weight = 0;             // N
  std::int64_t held_dofs = 0;
  std::int64_t mechanism_holds = 0;  // held dofs in parts supported along their axis
  double relative_floor = 0;         // the rounding floor / max |R(0, lambda)|
};

HeldBalance held_balance(const Scene& scene, const KeptRun& run) {
  const FinalState state = final_state(scene, run.result);
  const Model& model = state.model;
  const int dim = model.dim();
  const auto [part, supported] = supported_parts(model);
  const Vector force = model.internal_force(state.displacement) - model.external_force;
  const double load = max_abs(model.residual(Vector::Zero(model.dofs().free_count), state.lambda));
  HeldBalance result;
  double worst = 0;
  for (std::int64_t dof = 0; dof < model.dofs().dof_count(); ++dof) {
    const bool vertical = dof % dim == dim - 1;
    if (vertical) result.weight -= model.external_force[dof];
    if (model.dofs().free_index[dof] < 0) {
      if (vertical) result.support_reaction += force[dof];
    } else if (run.model.dofs().free_index[dof] < 0) {
      ++result.held_dofs;
      if (supported[part[dof / dim]][dof % dim]) ++result.mechanism_holds;
      if (vertical) result.holding_force += force[dof];
    } else {
      worst = std::max(worst, std::abs(force[dof]));
    }
  }
  result.relative_residual = load > 0 ? worst / load : worst;
  // The rounding floor of this state, 16 eps max(|K| |u| + |f|) over the free dofs: no
  // solve in double precision can go below it (docs/robustness.md).
  StiffnessMatrix stiffness(model);
  stiffness.assemble(model, state.displacement);
  const Vector u = model.free_part(state.displacement);
  Vector size = model.free_part(model.external_force).cwiseAbs();
  const auto& start = stiffness.column_start();
  const auto& row = stiffness.row_index();
  const auto& value = stiffness.values();
  for (std::int64_t j = 0; j < stiffness.size(); ++j) {
    for (std::int64_t k = start[j]; k < start[j + 1]; ++k) {
      size[row[k]] += std::abs(value[k] * u[j]);
      if (row[k] != j) size[j] += std::abs(value[k] * u[row[k]]);
    }
  }
  const double floor = 16 * std::numeric_limits<double>::epsilon() * max_abs(size);
  result.relative_floor = load > 0 ? floor / load : floor;
  return result;
}

HeldBalance check_held_equilibrium(const Scene& scene, const KeptRun& run) {
  CHECK(snapshots_finite(run.result));
  const HeldBalance b = held_balance(scene, run);
  INFO("relative residual " << b.relative_residual << ", support " << b.support_reaction
                            << " N, holding " << b.holding_force << " N, weight " << b.weight
                            << " N, held dofs " << b.held_dofs << ", for mechanisms "
                            << b.mechanism_holds << ", breaks " << run.result.summary.breaks);
  // 1e-9 of the load, or the rounding floor where pieces sag by kilometres, which the
  // solver accepts up to 100 times its tolerance of 1e-10.
  INFO("rounding floor " << b.relative_floor << " of the load");
  CHECK(b.relative_residual <= std::max(1e-9, std::min(b.relative_floor, 1e-8)));
  if (scene.gravity) CHECK(b.support_reaction + b.holding_force == Approx(b.weight).epsilon(1e-9));
  return b;
}

// A small crust after the paper's Fig. 6 (problems/fig6-elliptic-graben-2d.toml) without
// its pre-cut: 2-D 16 x 8 spacings or 3-D 6 x 3 x 4, a = 1 km, extension and gravity,
// fixed steps, sigma0 20 MPa (2-D) or 50 MPa (3-D): it breaks from the first step on.
Scene graben_scene(int dim, double poisson, Criterion criterion) {
  Scene scene = dim == 2 ? box_scene(2, 1000.0, {16e3, 0, 8e3}, true)
                         : box_scene(3, 1000.0, {6e3, 3e3, 4e3}, true);
  scene.material = paper_material(poisson);
  scene.strength = strength_of(criterion, dim == 2 ? 20e6 : 50e6, 34);
  scene.strength->tau0_factor = 3;
  scene.loading.total = 0.01;
  scene.stepping = {SteppingMethod::fixed, 1e-3};
  return scene;
}

}  // namespace

TEST_CASE("Hard: at nu = 1/4 the mechanisms that breaking leaves are held, 2-D and 3-D", "[hard]") {
  // Without shear springs a piece joined to the rest at one node turns about it: a pivot of
  // 1e-13 of its diagonal that the smallest-to-largest test let through, then "too
  // ill-conditioned" (issue 21).
  for (const int dim : {2, 3}) {
    for (const bool contact : {false, true}) {
      INFO(dim << "-D, contact " << contact);
      Scene scene = graben_scene(dim, 0.25, Criterion::elliptic);
      if (contact) scene.contact = Contact{};
      KeptRun run;
      REQUIRE_NOTHROW(run = run_keeping_model(scene));
      const HeldBalance b = check_held_equilibrium(scene, run);
      CHECK(run.result.summary.breaks > 0);
      // Without contact only a singular or mechanism pivot holds a single unknown.
      const auto single = std::count_if(run.result.fragments.begin(), run.result.fragments.end(),
                                        [](const FragmentEvent& f) { return f.nodes == 1; });
      INFO(single << " single unknowns held, " << b.mechanism_holds << " in supported parts");
      if (!contact) CHECK(single > 0);
    }
  }
}

TEST_CASE("Hard: massive breaking under strong gravity ends in equilibrium", "[hard]") {
  // Spread 0.99 leaves bonds of 1 % strength; g = 30 breaks most of the body at lambda 0
  // and leaves pieces that hang on a few bonds and sag by kilometres. Their residual sits
  // at the rounding floor of those displacements.
  Scene scene = box_scene(2, 1000.0, {16e3, 0, 8e3}, true);
  scene.gravity = Gravity{30.0};
  scene.strength = strength_of(Criterion::drucker_prager, 50e6, 10);
  scene.heterogeneity = Heterogeneity{0.99, 1};
  scene.loading.total = 0.01;
  scene.stepping = {SteppingMethod::fixed, 3e-4};
  KeptRun run;
  REQUIRE_NOTHROW(run = run_keeping_model(scene));
  check_held_equilibrium(scene, run);
  CHECK(run.result.summary.breaks > 0);
}

TEST_CASE(
    "Hard: a random search over nu, heterogeneity, gravity and criteria meets no "
    "ill-conditioned ending",
    "[hard]") {
  // nu in [0.2, 0.25] (a quarter of the scenes at 1/4 exactly), spread in [0.5, 0.99],
  // g in [0, 30], the four criteria, 2-D and 3-D, fixed steps and events, contact by
  // chance. Before the mechanism rule, the option mixes this searches over ended with
  // "too ill-conditioned" in 5 of 90 runs of the shipped scenes.
  const auto start = std::chrono::steady_clock::now();
  const int scenes = 200;
  std::int64_t mechanism_holds = 0;
  for (int trial = 0; trial < scenes; ++trial) {
    std::mt19937 random(2100 + trial);
    std::uniform_real_distribution<double> u(0, 1);
    const int dim = u(random) < 0.7 ? 2 : 3;
    const double poisson = u(random) < 0.25 ? 0.25 : 0.2 + 0.05 * u(random);
    const auto criterion = static_cast<Criterion>(static_cast<int>(4 * u(random)));
    Scene scene = graben_scene(dim, poisson, criterion);
    scene.heterogeneity = Heterogeneity{0.5 + 0.49 * u(random), static_cast<std::uint64_t>(trial)};
    const double g = 30 * u(random);
    scene.gravity = g > 0 ? std::optional<Gravity>(Gravity{g}) : std::nullopt;
    scene.strength->friction_angle = 10 + 30 * u(random);
    scene.strength->sigma0 = 1e6 * (10 + 90 * u(random));
    if (u(random) < 0.3) scene.contact = Contact{};
    if (u(random) < 0.5) scene.stepping = {SteppingMethod::event, 0};
    INFO("trial " << trial << ": " << dim << "-D, nu " << poisson << ", criterion "
                  << static_cast<int>(criterion) << ", spread " << scene.heterogeneity->spread
                  << ", g " << g);
    KeptRun run;
    REQUIRE_NOTHROW(run = run_keeping_model(scene));
    mechanism_holds += check_held_equilibrium(scene, run).mechanism_holds;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  WARN(scenes << " scenes in " << seconds << " s, " << mechanism_holds
              << " dofs held for mechanisms");
}

TEST_CASE("Hard: a mechanism that a downdate leaves is held at once, whatever the ordering",
          "[hard]") {
  // The 3-D reference block at 5000 m, event-driven, with contact: at lambda 0.0308 the
  // last spring along one unknown's axis is downdated away (docs/robustness.md,
  // "Mechanisms"). A fresh factorization at every solve holds it there; with factor
  // updates, the updated pivot came out positive with AMD and NESDIS ordering (the run
  // solved on with it) and negative with METIS (held late, at lambda 0.0334, where it had
  // drifted), and the cascade's f differed by 1.4 %. With the pivots checked after each
  // update, every ordering holds it at the same lambda as the fresh factorizations, and
  // the events agree to rounding, f included.
  const auto run_with = [](Ordering ordering, std::int64_t refactor_every) {
    Scene scene = read_problem_file(std::string(LATFRAC_PROBLEMS_DIR) + "/reference-3d.toml",
                                    {"lattice.spacing=5000", "stepping.method=\"event\"",
                                     "output.snapshots=[0.04]"});
    scene.solver.ordering = ordering;
    scene.solver.refactor_every = refactor_every;
    return run_scene(scene, quiet());
  };
  // The reference: a fresh factorization at every solve, which holds the mechanism.
  const RunResult fresh = run_with(Ordering::metis, 1);
  REQUIRE(fresh.fragments.size() >= 2);
  const double mechanism_lambda = fresh.fragments[1].lambda;
  for (const Ordering ordering : {Ordering::metis, Ordering::amd, Ordering::nesdis}) {
    const RunResult updated = run_with(ordering, 200);
    INFO("ordering " << static_cast<int>(ordering));
    REQUIRE(updated.fragments.size() == fresh.fragments.size());
    CHECK(updated.fragments[1].lambda == Approx(mechanism_lambda).epsilon(1e-12));
    REQUIRE(updated.events.size() == fresh.events.size());
    for (std::size_t e = 0; e < fresh.events.size(); ++e) {
      INFO("event " << e);
      CHECK(updated.events[e].bond == fresh.events[e].bond);
      CHECK(updated.events[e].lambda == Approx(fresh.events[e].lambda).epsilon(1e-9));
      CHECK(updated.events[e].failure_index ==
            Approx(fresh.events[e].failure_index).epsilon(1e-9));
    }
  }
}
