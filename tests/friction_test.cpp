// Coulomb friction on closed contacts (friction_law.h): a block pressed on a plane and
// pushed sideways, against the hand calculation; energy balance; the cycle guard; and
// mu = 0 identical to the frictionless contact.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "latfrac/base/progress.h"
#include "latfrac/criteria/criterion.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/fracture/break_source.h"
#include "latfrac/fracture/breaking.h"
#include "latfrac/fracture/event_loop.h"
#include "latfrac/fracture/pair_settling.h"
#include "latfrac/fracture/pair_switch_source.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/scene/run.h"
#include "hard_case_checks.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

// The block: node 0 (the plane) fixed at the origin; node 1 (the block) 1 m above it,
// free, pressed down by P; node 2 (the pusher) 1 m to its right, its x prescribed at
// lambda (1 m per unit lambda), its z free. Bond 0 (0-1) is a pre-cut contact (kn_c,
// ks_c); bond 1 (1-2) an intact spring (kn2 along x, ks2 along z) that pushes the block.
// Node 2's z carries nothing but bond 1's shear, so the contact's normal force is P.
struct Block {
  static constexpr double P = 1e6, kn_c = 1e9, ks_c = 4e8, kn2 = 2e8, ks2 = 1e8, mu = 0.5;
  Model model;
  // Without the pusher (nodes 0 and 1, bond 0 only), node 1 also carries a sideways force
  // `sideways` (N): the block is held by friction alone.
  explicit Block(bool pusher = true, double sideways = 0) {
    const std::size_t nodes = pusher ? 3 : 2, bonds = pusher ? 2 : 1;
    auto first = [](auto all, std::size_t count) {
      all.resize(count);
      return all;
    };
    Lattice& l = model.lattice;
    l.dim = 2;
    l.spacing = 1;
    l.node_volume = 1;
    l.extent = {1, 0, 1};
    l.positions = first(std::vector<Vec3>{{0, 0, 0}, {0, 0, 1}, {1, 0, 1}}, nodes);
    l.face_mask.assign(nodes, 0);
    l.bonds = first(std::vector<Bond>{{0, 1, BondKind::nearest}, {1, 2, BondKind::nearest}}, bonds);
    l.bond_direction = first(std::vector<Vec3>{{0, 0, 1}, {1, 0, 0}}, bonds);
    l.bond_length.assign(bonds, 1);
    model.normal_stiffness = first(std::vector<double>{kn_c, kn2}, bonds);
    model.shear_stiffness = first(std::vector<double>{ks_c, ks2}, bonds);
    model.precut = first(std::vector<std::uint8_t>{1, 0}, bonds);
    model.bond_young.assign(bonds, 1e9);
    model.bond_shear_modulus.assign(bonds, 4e8);
    model.bond_sigma0.assign(bonds, 1e30);  // nothing breaks
    model.bond_tau0.assign(bonds, 1e30);
    model.node_poisson.assign(nodes, 0.2);
    model.external_force = Vector::Zero(2 * nodes);
    model.external_force[2] = sideways;  // node 1, x
    model.external_force[3] = -P;        // node 1, z
    DofMap dofs;
    dofs.dim = 2;
    dofs.free_index = first(std::vector<std::int64_t>{-1, -1, 0, 1, -1, 2}, 2 * nodes);
    dofs.prescribed_base.assign(2 * nodes, 0);
    dofs.prescribed_rate.assign(2 * nodes, 0);
    if (pusher) dofs.prescribed_rate[4] = 1;  // node 2, x
    dofs.free_count = pusher ? 3 : 2;
    ModelEditor editor(model);
    editor.reset_states();
    editor.set_dofs(dofs);
    editor.set_laws(std::make_unique<SmallKinematics>(2),
                    std::make_unique<FrictionalContactLaw>(1.0, mu));
    editor.set_state(0, PairState::closed);
  }
};

// The run's machinery, driven by hand so that lambda can go back (unloading).
struct Driver {
  SolverOptions options;
  EquilibriumSolver solver;
  EquilibriumState equilibrium;
  PairSettling settling;
  FailureEvaluator evaluator;
  ProgressLine progress{false};
  RunResult result;
  Breaking breaking;
  BreakSource breaks;
  PairSwitchSource switches;
  std::vector<double> switch_lambdas;
  Driver(Model& model, Strength strength)
      : solver(model, options),
        equilibrium(model, solver, options),
        settling(equilibrium),
        evaluator(strength, model),
        breaking(equilibrium, settling, evaluator, progress, result),
        breaks(equilibrium, evaluator, breaking),
        switches(equilibrium, settling, breaking) {}
  void follow(double from, double to) {
    std::vector<PairState> before = equilibrium.model().pair_states();
    follow_events(equilibrium, {&breaks, &switches}, from, to, [](double) {},
                  [&](double lambda) {
                    if (equilibrium.model().pair_states() != before)
                      switch_lambdas.push_back(lambda);
                    before = equilibrium.model().pair_states();
                  });
    equilibrium.commit_contacts(to);
  }
};

Strength unbreakable() {
  Strength strength = strength_of(Criterion::tensile, 1e30);
  return strength;
}

}  // namespace

TEST_CASE("Friction: a pushed block slips where |Ft| = mu Fn, sticks again on unloading, and "
          "slips back where the hand calculation says",
          "[friction]") {
  Block block;
  Driver run(block.model, unbreakable());
  const double mu = Block::mu, P = Block::P, kc = Block::ks_c, k2 = Block::kn2;
  // Stick: the block's x follows ks_c (u1 - 0) = kn2 (lambda - u1), so Ft = ks_c kn2 lambda /
  // (ks_c + kn2), which reaches mu P at lambda* below.
  const double onset = mu * P * (kc + k2) / (kc * k2);
  run.follow(0, 0.01);
  REQUIRE(run.switch_lambdas.size() == 1);
  CHECK(run.switch_lambdas[0] == Approx(onset).epsilon(1e-10));
  CHECK(block.model.state(0) == PairState::slip);
  // Slipping, Ft = mu P: u1 = lambda - mu P / kn2; the anchor (u1 - mu P / ks_c) moved from
  // 0 to there.
  const double slip_out = 0.01 - mu * P / k2 - mu * P / kc;
  const ContactMemory& m = block.model.contact_memory()[0];
  CHECK(m.slip == Approx(slip_out).epsilon(1e-10));
  CHECK(m.work == Approx(mu * P * slip_out).epsilon(1e-10));
  const Vector u = run.equilibrium.displacement(0.01);
  CHECK(u[2] == Approx(0.01 - mu * P / k2).epsilon(1e-10));
  CHECK(u[3] == Approx(-P / Block::kn_c).epsilon(1e-10));

  // Unloading: the slip rate turns at once, so the block sticks at lambda = 0.01 with its
  // anchor at slip_out; Ft = ks_c kn2 (lambda - slip_out) / (ks_c + kn2) reaches -mu P at
  // lambda = slip_out - onset, and from there it slips back.
  run.switch_lambdas.clear();
  run.follow(0.01, 0.002);
  REQUIRE(run.switch_lambdas.size() == 2);
  CHECK(run.switch_lambdas[0] == 0.01);
  CHECK(run.switch_lambdas[1] == Approx(slip_out - onset).epsilon(1e-10));
  CHECK(block.model.state(0) == PairState::slip);
  const double slip_back = (slip_out - onset) - 0.002;
  CHECK(m.slip == Approx(slip_out + slip_back).epsilon(1e-10));
  CHECK(m.work == Approx(mu * P * (slip_out + slip_back)).epsilon(1e-10));
  // The equilibrium is exact with the nonsymmetric slip force (the Woodbury solve).
  CHECK(run.solver.counters().coupled_solves > 0);
}

namespace {

// A 12 x 8 m box (a = 1 m, no gravity) cut through by a fault dipping 53 deg, pressed by
// its walls (loading.total < 0); nothing can break. With a small mu the hanging wall
// slides up the fault.
Scene fault_scene(double mu, double total = -2e-3) {
  Scene scene = box_scene(2, 1.0, {12.0, 0, 8.0}, false);
  scene.strength = strength_of(Criterion::tensile, 1e15);
  scene.contact = Contact{true, mu};
  scene.precuts.push_back({{3.1, 0, -0.5}, {9.1, 0, 8.5}, {}, {}, {}});
  scene.loading.total = total;
  return scene;
}

// The energy stored in the springs and contacts at the full displacement u. A slipping
// contact's tangential spring holds mu |Fn| (the force at which it slips): (mu kn dn)^2 /
// (2 ks).
double stored_energy(const Model& model, const Vector& u, double mu) {
  double energy = 0;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    const PairSprings springs = model.springs(b);
    const Vec3 du = model.bond_displacement(u, b);
    const double dn = springs.direction.dot(du);
    const Vec3 tangential = du - dn * springs.direction;
    switch (model.state(b)) {
      case PairState::intact:
        energy += 0.5 * (springs.kn * dn * dn + springs.ks * tangential.squaredNorm());
        break;
      case PairState::closed:
        if (!model.contact_capable(b)) break;
        energy += 0.5 * springs.kn * dn * dn;
        if (springs.memory)
          energy += 0.5 * springs.ks * (tangential - springs.memory->anchor).squaredNorm();
        break;
      case PairState::slip:
        energy += 0.5 * springs.kn * dn * dn + 0.5 * std::pow(mu * springs.kn * dn, 2) / springs.ks;
        break;
      default:
        break;
    }
  }
  return energy;
}

double friction_work(const Model& model) {
  double work = 0;
  for (const ContactMemory& m : model.contact_memory()) work += m.work;
  return work;
}

}  // namespace

TEST_CASE("Friction: external work = stored energy + work dissipated by friction, to 1e-8",
          "[friction]") {
  const Scene scene = fault_scene(0.3);
  Model model = build_model(scene);
  prepare_supports(model, "");
  Driver run(model, *scene.strength);
  run.settling.settle(0);
  run.equilibrium.commit_contacts(0);
  // Between two consecutive events the path is affine: the wall reactions are affine in
  // lambda (the trapezoidal rule is exact) and without breaks nothing jumps at an event.
  Vector u_last = run.equilibrium.displacement(0);
  Vector r_last = model.reactions(u_last);
  const double stored_start = stored_energy(model, u_last, 0.3);
  const double work_start = friction_work(model);
  double external = 0;
  auto add_work = [&](double lambda) {
    const Vector u = run.equilibrium.displacement(lambda);
    const Vector r = model.reactions(u);
    const Vector du = u - u_last;
    external += model.external_force.dot(du) + 0.5 * (r + r_last).dot(du);
    u_last = u;
    r_last = r;
  };
  int events = 0;
  follow_events(run.equilibrium, {&run.breaks, &run.switches}, 0, scene.loading.total,
                [](double) {},
                [&](double lambda) {
                  add_work(lambda);
                  ++events;
                });
  run.equilibrium.commit_contacts(scene.loading.total);
  const double stored = stored_energy(model, u_last, 0.3) - stored_start;
  const double dissipated = friction_work(model) - work_start;
  INFO("events " << events << ", external " << external << " J/m, stored " << stored
                 << ", friction " << dissipated);
  CHECK(run.result.events.empty());
  CHECK(dissipated > 1e-4 * external);  // the fault slid: 1e-8 of the work is 1e-4 of this
  CHECK(external == Approx(stored + dissipated).epsilon(1e-8));
}

TEST_CASE("Friction: with a large mu the fault sticks and nothing is dissipated", "[friction]") {
  const RunResult result = run_scene(fault_scene(5.0), quiet());
  CHECK(result.summary.friction_work == 0);
  CHECK(result.summary.contact_slip == 0);
  const RunResult sliding = run_scene(fault_scene(0.3), quiet());
  CHECK(sliding.summary.friction_work > 0);
  CHECK(sliding.summary.contact_slip > 0);
}

TEST_CASE("Friction: fixed-step runs converge to the event-driven run as ds shrinks",
          "[friction]") {
  Scene scene = fault_scene(0.3);
  const RunResult exact = run_scene(scene, quiet());
  std::vector<double> errors;
  for (const double ds : {2e-4, 2e-5}) {
    scene.stepping = {SteppingMethod::fixed, ds};
    const RunResult fixed = run_scene(scene, quiet());
    errors.push_back(std::abs(fixed.summary.friction_work / exact.summary.friction_work - 1));
  }
  INFO("relative error of the friction work at ds 2e-4, 2e-5: " << errors[0] << ", " << errors[1]);
  CHECK(errors[1] < 0.5 * errors[0]);
  CHECK(errors[1] < 1e-2);
}

TEST_CASE("Friction: a frictional contact with mu = 0 breaks the same bonds as the "
          "frictionless one",
          "[friction]") {
  // The frictionless law and the frictional law at mu = 0 (its contacts slip at zero
  // force; the slip states, the loads of anchors and the coupled solves all take part)
  // are two implementations of one physics.
  Scene scene = box_scene(2, 1.0, {12.0, 0, 8.0}, true);
  scene.strength = strength_of(Criterion::elliptic, 2e5);
  scene.strength->tau0_factor = 2;
  scene.contact = Contact{};
  scene.precuts.push_back({{3.1, 0, -0.5}, {9.1, 0, 8.5}, {}, {}, {}});
  scene.loading.total = -4e-3;
  Model frictionless = build_model(scene);
  const RunResult a = run_model(frictionless, scene);
  Model frictional = build_model(scene);
  ModelEditor(frictional).set_laws(std::make_unique<SmallKinematics>(2),
                                   std::make_unique<FrictionalContactLaw>(1.0, 0.0));
  const RunResult b = run_model(frictional, scene);
  INFO("breaks " << a.events.size() << " and " << b.events.size());
  REQUIRE(a.events.size() > 5);
  REQUIRE(a.events.size() == b.events.size());
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    INFO("event " << k);
    CHECK(a.events[k].bond == b.events[k].bond);
    CHECK(a.events[k].lambda == Approx(b.events[k].lambda).epsilon(1e-9));
  }
}

TEST_CASE("Friction: a block held by friction alone stays, and one that friction cannot hold is "
          "held by the mechanism rule, without NaN",
          "[friction][hard]") {
  const double P = Block::P, mu = Block::mu;
  {
    Block block(false, 0.8 * mu * P);  // within the cone: it sticks
    Driver run(block.model, unbreakable());
    run.settling.settle(0);
    run.follow(0, 0.01);
    CHECK(block.model.state(0) == PairState::closed);
    const Vector u = run.equilibrium.displacement(0.01);
    CHECK(u[2] == Approx(0.8 * mu * P / Block::ks_c).epsilon(1e-10));
    CHECK(u[3] == Approx(-P / Block::kn_c).epsilon(1e-10));
    CHECK(run.equilibrium.fragments().empty());
  }
  {
    // Beyond the cone the block slips, and slipping it has no sideways stiffness: the
    // stiffness is singular, and the block is held where it stands.
    Block block(false, 1.2 * mu * P);
    Driver run(block.model, unbreakable());
    REQUIRE_NOTHROW(run.settling.settle(0));
    REQUIRE_NOTHROW(run.follow(0, 0.01));
    const Vector u = run.equilibrium.displacement(0.01);
    CHECK(u.allFinite());
    CHECK(block.model.dofs().free_count < 2);
  }
}

TEST_CASE("Hard: Fig. 6 with mu = 0.6, whose contacts stick and slip back and forth, finishes "
          "the same on every run",
          "[friction][hard]") {
  // At 3000 m the scene's contacts meet the cycle rule and the unstable-contact rule
  // (docs/robustness.md) 16 times; without them the run does not end.
  const Scene scene = read_problem_file(
      std::string(LATFRAC_PROBLEMS_DIR) + "/fig6-elliptic-graben-2d.toml",
      {"stepping.method=\"event\"", "contact.friction=0.6", "lattice.spacing=3000",
       "output.snapshots=[0.04]"});
  const RunResult a = run_scene(scene, quiet());
  CHECK(a.summary.contact_cycles >= 1);
  CHECK(a.summary.friction_work > 0);
  CHECK(snapshots_finite(a));
  CHECK(all_finite(a.friction_work));
  const RunResult b = run_scene(scene, quiet());
  check_same_events(a, b);
  CHECK(a.summary.friction_work == b.summary.friction_work);
}
