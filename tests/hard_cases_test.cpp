// Hard cases: isolated nodes and shattered regions, extreme increments, stiffness
// contrasts, collapse under gravity alone, degenerate boxes, factor drift and ties.
//
// Each case checks an expectation that does not come from the code under test: the
// equilibrium residual recomputed on a freshly built model, the support reactions against
// the total weight, the lithostatic column, a fresh factorization, determinism.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include "latfrac/error.h"

#include "final_state.h"
#include "latfrac/equilibrium.h"
#include "latfrac/fragments.h"
#include "latfrac/node_stress.h"
#include "latfrac/run.h"
#include "random_breaks.h"
#include "scenes.h"

using namespace latfrac;
using testing::strength_of;

namespace {

using testing::final_state;
using testing::FinalState;

RunOptions quiet() {
  RunOptions options;
  options.progress = false;
  return options;
}

bool all_finite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

bool snapshots_finite(const RunResult& result) {
  for (const Snapshot& s : result.snapshots) {
    if (!all_finite(s.displacement) || !all_finite(s.node_stress) ||
        !all_finite(s.bond_failure_index))
      return false;
  }
  return true;
}

// Equilibrium of a final state, part by part. The connected parts (intact bonds) are found
// here, independently of the run. A part with no prescribed dof along an axis in the fresh
// model must have been held along it by the run (docs/robustness.md): the force on those
// dofs is the holding force. Everywhere else the residual must vanish.
struct Balance {
  double relative_residual =
      0;  // max |R| over the free dofs of supported parts / max |R(0, lambda)|
  double support_reaction = 0;  // vertical reactions of the prescribed dofs (N), upward positive
  double holding_force = 0;     // vertical forces that hold parts without vertical support
  double weight = 0;            // total gravity force (N), positive
  std::int64_t held_nodes = 0;  // nodes of parts without support along some axis
};

Balance balance(const FinalState& state) {
  const Model& model = state.model;
  const Lattice& lattice = model.lattice;
  const int dim = model.dim();
  const std::int64_t nodes = lattice.node_count();
  std::vector<std::vector<std::int64_t>> neighbours(nodes);
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    if (!model.intact[b]) continue;
    neighbours[lattice.bonds[b].i].push_back(lattice.bonds[b].j);
    neighbours[lattice.bonds[b].j].push_back(lattice.bonds[b].i);
  }
  std::vector<std::int64_t> part(nodes, -1);
  std::vector<std::array<bool, 3>> supported;
  for (std::int64_t start = 0; start < nodes; ++start) {
    if (part[start] >= 0) continue;
    const std::int64_t id = static_cast<std::int64_t>(supported.size());
    supported.push_back({false, false, false});
    std::vector<std::int64_t> queue{start};
    part[start] = id;
    for (std::size_t k = 0; k < queue.size(); ++k) {
      const std::int64_t n = queue[k];
      for (int c = 0; c < dim; ++c)
        supported[id][c] = supported[id][c] || model.dofs.free_index[n * dim + c] < 0;
      for (std::int64_t next : neighbours[n]) {
        if (part[next] < 0) {
          part[next] = id;
          queue.push_back(next);
        }
      }
    }
  }
  const Vector force = model.internal_force(state.displacement) - model.external_force;
  const Vector unloaded = model.residual(Vector::Zero(model.dofs.free_count), state.lambda);
  const double load = max_abs(unloaded);
  Balance result;
  double worst = 0;
  std::vector<std::uint8_t> held(nodes, 0);
  for (std::int64_t n = 0; n < nodes; ++n) {
    for (int c = 0; c < dim; ++c) {
      const std::int64_t dof = n * dim + c;
      const bool vertical = c == dim - 1;
      if (vertical) result.weight -= model.external_force[dof];
      if (model.dofs.free_index[dof] < 0) {
        if (vertical) result.support_reaction += force[dof];
      } else if (supported[part[n]][c]) {
        worst = std::max(worst, std::abs(force[dof]));
      } else {
        held[n] = 1;
        if (vertical) result.holding_force += force[dof];
      }
    }
  }
  result.held_nodes = std::count(held.begin(), held.end(), 1);
  result.relative_residual = load > 0 ? worst / load : worst;
  return result;
}

std::int64_t node_nearest(const Lattice& lattice, const Vec3& point) {
  std::int64_t best = 0;
  for (std::int64_t n = 1; n < lattice.node_count(); ++n) {
    if ((lattice.positions[n] - point).norm() < (lattice.positions[best] - point).norm()) best = n;
  }
  return best;
}

// Six short cuts forming a hexagon of radius a/2 around node `centre`: each of its six
// bonds crosses one edge at its midpoint, and no other bond comes near.
std::vector<Precut> hexagon_around(const Vec3& centre, double spacing) {
  std::vector<Precut> cuts;
  const double pi = std::acos(-1.0);
  auto vertex = [&](int k) {
    const double angle = (30.0 + 60.0 * k) * pi / 180.0;
    return std::array<double, 3>{centre.x() + 0.5 * spacing * std::cos(angle), 0.0,
                                 centre.z() + 0.5 * spacing * std::sin(angle)};
  };
  for (int k = 0; k < 6; ++k) cuts.push_back({vertex(k), vertex(k + 1), {}, {}, {}});
  return cuts;
}

std::set<std::int64_t> broken_set(const RunResult& result) {
  std::set<std::int64_t> broken;
  for (const BreakEvent& e : result.events) {
    if (e.mode != 2) broken.insert(e.bond);
  }
  return broken;
}

void check_same_events(const RunResult& a, const RunResult& b) {
  REQUIRE(a.events.size() == b.events.size());
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    INFO("event " << k);
    CHECK(a.events[k].bond == b.events[k].bond);
    CHECK(a.events[k].lambda == b.events[k].lambda);
    CHECK(a.events[k].failure_index == b.events[k].failure_index);
    CHECK(a.events[k].mode == b.events[k].mode);
    CHECK(a.events[k].cascade == b.events[k].cascade);
  }
  REQUIRE(a.fragments.size() == b.fragments.size());
  for (std::size_t k = 0; k < a.fragments.size(); ++k) {
    CHECK(a.fragments[k].lambda == b.fragments[k].lambda);
    CHECK(a.fragments[k].nodes == b.fragments[k].nodes);
  }
}

// The final state is in equilibrium where nothing is held, and the supports plus the
// holding forces carry the whole weight.
void check_final_equilibrium(const Scene& scene, const RunResult& result, double tolerance = 1e-9) {
  REQUIRE(!result.snapshots.empty());
  const FinalState state = final_state(scene, result);
  const Balance b = balance(state);
  INFO("relative residual " << b.relative_residual << ", support " << b.support_reaction
                            << " N, holding " << b.holding_force << " N, weight " << b.weight
                            << " N, held nodes " << b.held_nodes << ", parts held "
                            << result.fragments.size());
  CHECK(b.relative_residual <= tolerance);
  if (result.fragments.empty()) CHECK(b.held_nodes == 0);
  if (scene.gravity) {
    CHECK(b.support_reaction + b.holding_force == Approx(b.weight).epsilon(1e-9));
    if (b.held_nodes == 0) CHECK(b.support_reaction == Approx(b.weight).epsilon(1e-9));
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// 1. Fragments

TEST_CASE("Hard: a node isolated by pre-cuts is held, reported, and never NaN", "[hard]") {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, true);
  scene.strength = strength_of(Criterion::tensile, 50e6);
  scene.loading.total = 1e-3;
  scene.stepping = {SteppingMethod::event, 0};
  const Lattice lattice = build_lattice(scene.lattice);
  const std::int64_t centre = node_nearest(lattice, {10.0, 0, 5.0});
  scene.precuts = hexagon_around(lattice.positions[centre], 1.0);
  const RunResult result = run_scene(scene, quiet());
  std::int64_t precut_events = 0;
  for (const BreakEvent& e : result.events) {
    if (e.mode != 2) continue;
    ++precut_events;
    const Bond& bond = lattice.bonds[e.bond];
    CHECK((bond.i == centre || bond.j == centre));
  }
  CHECK(precut_events == 6);
  // The hole concentrates stress, and the fracture it starts may cut more parts loose
  // later; the isolated node is the first part held, at the start.
  REQUIRE(!result.fragments.empty());
  CHECK(result.fragments[0].nodes == 1);
  CHECK(result.fragments[0].lambda == 0.0);
  CHECK(result.summary.breaks > 0);
  CHECK(snapshots_finite(result));
  // Held where it started, along both axes; every part that kept its support in equilibrium.
  const Snapshot& last = result.snapshots.back();
  for (int k = 0; k < 3; ++k) CHECK(last.displacement[3 * centre + k] == 0.0);
  check_final_equilibrium(scene, result);
  CHECK(balance(final_state(scene, result)).held_nodes >= 1);
}

TEST_CASE("Hard: a cascade that shatters a weak band finishes with every held part accounted for",
          "[hard]") {
  // Tensile strength 50 MPa except a band 4 m <= z < 6 m at 1 kPa: extension shatters it.
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, true);
  scene.strength = strength_of(Criterion::tensile, 50e6);
  Layer weak;
  weak.z_min = 4.0;
  weak.z_max = 6.0;
  weak.material = scene.material;
  weak.sigma0 = 1e3;
  scene.layers.push_back(weak);
  scene.loading.total = 2e-4;
  scene.stepping = {SteppingMethod::event, 0};
  const RunResult result = run_scene(scene, quiet());
  CHECK(snapshots_finite(result));
  CHECK(result.summary.breaks > 20);
  INFO("breaks " << result.summary.breaks << ", parts held " << result.fragments.size());
  check_final_equilibrium(scene, result);
  // Determinism of the whole cascade.
  check_same_events(result, run_scene(scene, quiet()));
}

// ---------------------------------------------------------------------------------------
// 2. Increments

TEST_CASE("Hard: fixed steps of 1e-7 over 20 steps end in equilibrium", "[hard]") {
  // Horizontal bonds reach the tensile strength 100 kPa at lambda = 1e-6, step 10.
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, true);
  scene.strength = strength_of(Criterion::tensile, 1e5);
  scene.loading.total = 2e-6;
  scene.stepping = {SteppingMethod::fixed, 1e-7};
  scene.output.snapshots = {1e-6, 2e-6};
  const RunResult result = run_scene(scene, quiet());
  REQUIRE(result.snapshots.size() == 2);
  CHECK(result.snapshots.back().lambda == 2e-6);
  CHECK(snapshots_finite(result));
  INFO("breaks " << result.summary.breaks << ", parts held " << result.fragments.size());
  CHECK(result.summary.breaks > 0);
  for (const BreakEvent& e : result.events) {
    // Every break sits on a step k * 1e-7 (no break before the strength is reached).
    const double steps = e.lambda / 1e-7;
    CHECK(std::abs(steps - std::round(steps)) < 1e-6);
    CHECK(e.lambda >= 1e-6 * (1 - 1e-9));
    CHECK(e.failure_index >= 1.0);
  }
  check_final_equilibrium(scene, result);
}

TEST_CASE("Hard: one fixed step straight to lambda 0.04 shatters deterministically", "[hard]") {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, true);
  scene.strength = strength_of(Criterion::elliptic, 50e6);
  scene.loading.total = 0.04;
  scene.stepping = {SteppingMethod::fixed, 0.04};
  const RunResult result = run_scene(scene, quiet());
  CHECK(snapshots_finite(result));
  INFO("breaks " << result.summary.breaks << ", parts held " << result.fragments.size());
  CHECK(result.summary.breaks > 0);
  for (const BreakEvent& e : result.events) CHECK((e.lambda == 0.0 || e.lambda == 0.04));
  check_final_equilibrium(scene, result);
  const RunResult again = run_scene(scene, quiet());
  CHECK(broken_set(again) == broken_set(result));
  check_same_events(result, again);
  CHECK(again.snapshots.back().displacement == result.snapshots.back().displacement);
}

// ---------------------------------------------------------------------------------------
// 3. Stiffness contrast

namespace {

Scene contrast_scene(double spacing, double length, double height, double upper_young) {
  Scene scene = testing::box_scene(2, spacing, {length, 0, height}, true);
  Layer upper;
  upper.z_min = height / 2;
  upper.z_max = 1e3 * height;  // above the top row
  upper.material = scene.material;
  upper.material.young = upper_young;
  scene.layers.push_back(upper);
  return scene;
}

}  // namespace

TEST_CASE("Hard: lithostatic stress holds in both layers of a 1e4 stiffness contrast", "[hard]") {
  const double upper_young = GENERATE(1e13, 1e7);  // stiff on soft, soft on stiff
  const double height = 10e3, length = 40e3;
  const Scene scene = contrast_scene(500.0, length, height, upper_young);
  const RunResult result = run_scene(scene, quiet());
  REQUIRE(result.snapshots.size() == 1);
  CHECK(snapshots_finite(result));
  const FinalState state = final_state(scene, result);
  CHECK(balance(state).relative_residual <= 1e-9);
  const Lattice& lattice = state.model.lattice;
  const std::vector<double> stress = node_stresses(state.model, state.displacement);
  const double surface = lattice.extent.z() + lattice.row_pitch / 2;
  const double rho_g = scene.material.density * 9.81;
  for (const double mid : {0.25 * height, 0.75 * height}) {
    int checked = 0;
    double worst = 0;
    for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
      const Vec3& p = lattice.positions[n];
      if (std::abs(p.z() - mid) > 0.6 * lattice.row_pitch) continue;  // the row(s) at mid-depth
      if (std::abs(p.x() - lattice.extent.x() / 2) > 0.15 * lattice.extent.x()) continue;
      worst = std::max(worst, std::abs(stress[6 * n + 2] / (-rho_g * (surface - p.z())) - 1));
      ++checked;
    }
    INFO("upper E " << upper_young << ", mid-depth z " << mid << ": " << checked << " nodes, worst "
                    << worst);
    CHECK(checked >= 10);
    CHECK(worst < 0.02);
  }
}

TEST_CASE("Hard: fracture across a 1e4 stiffness contrast stays in equilibrium", "[hard]") {
  const double upper_young = GENERATE(1e13, 1e7);
  Scene scene = contrast_scene(1000.0, 16e3, 8e3, upper_young);
  scene.strength = strength_of(Criterion::elliptic, 50e6, 34.0);
  scene.strength->tau0_factor = 3.0;
  scene.precuts.push_back({{8250, 0, 9000}, {8250, 0, 5500}, {}, {}, {}});
  scene.loading.total = 2e-3;
  scene.stepping = {SteppingMethod::event, 0};
  const RunResult result = run_scene(scene, quiet());
  CHECK(snapshots_finite(result));
  WARN("contrast upper E " << upper_young << ": breaks " << result.summary.breaks << ", parts held "
                           << result.fragments.size() << ", solves " << result.summary.solves
                           << ", factorizations " << result.summary.factorizations
                           << ", factor updates " << result.summary.factor_updates);
  CHECK(result.summary.breaks > 0);
  check_final_equilibrium(scene, result);
}

// ---------------------------------------------------------------------------------------
// 4. Collapse under gravity alone

TEST_CASE("Hard: a body too weak for its own weight collapses in a cascade at lambda 0", "[hard]") {
  const SteppingMethod method = GENERATE(SteppingMethod::event, SteppingMethod::fixed);
  Scene scene = testing::box_scene(2, 1000.0, {16e3, 0, 8e3}, true);
  scene.strength = strength_of(Criterion::elliptic, 1e5);
  scene.loading.total = 0;
  scene.stepping = {method, 1e-3};
  const RunResult result = run_scene(scene, quiet());
  REQUIRE(!result.events.empty());
  for (const BreakEvent& e : result.events) {
    CHECK(e.lambda == 0.0);
    CHECK(e.mode != 2);
  }
  CHECK(result.summary.breaks == static_cast<std::int64_t>(result.events.size()));
  REQUIRE(result.snapshots.size() == 1);
  CHECK(result.snapshots[0].lambda == 0.0);
  CHECK(snapshots_finite(result));
  INFO("breaks " << result.summary.breaks << " of " << result.bond_count() << ", parts held "
                 << result.fragments.size());
  check_final_equilibrium(scene, result);
}

// ---------------------------------------------------------------------------------------
// 5. Degenerate inputs

TEST_CASE("Hard: the smallest lattices, with and without gravity", "[hard]") {
  const int dim = GENERATE(2, 3);
  const bool gravity = GENERATE(false, true);
  const double total = GENERATE(0.0, 1e-3);
  Scene scene = testing::box_scene(dim, 1.0, {2.0, 2.0, 2.0}, gravity);
  scene.loading.total = total;
  INFO(dim << "-D, gravity " << gravity << ", lambda " << total);
  const RunResult result = run_scene(scene, quiet());
  REQUIRE(result.snapshots.size() == 1);
  CHECK(snapshots_finite(result));
  const Snapshot& last = result.snapshots.back();
  if (!gravity && total == 0) {
    for (double u : last.displacement) CHECK(u == 0.0);
    for (double s : last.node_stress) CHECK(s == 0.0);
  } else {
    CHECK(std::any_of(last.displacement.begin(), last.displacement.end(),
                      [](double u) { return u != 0.0; }));
  }
  check_final_equilibrium(scene, result);
}

TEST_CASE("Hard: extreme aspect ratios, 200 x 2 and 2 x 100 spacings", "[hard]") {
  const bool wide = GENERATE(true, false);
  Scene scene = testing::box_scene(
      2, 1.0, wide ? std::array<double, 3>{200.0, 0, 2.0} : std::array<double, 3>{2.0, 0, 100.0},
      true);
  scene.loading.total = 1e-3;
  INFO((wide ? "200 x 2" : "2 x 100"));
  const RunResult result = run_scene(scene, quiet());
  CHECK(snapshots_finite(result));
  check_final_equilibrium(scene, result);
  // The same with fracture: the thin body breaks through, the run still balances.
  scene.strength = strength_of(Criterion::tensile, 50e6);
  scene.stepping = {SteppingMethod::event, 0};
  const RunResult broken = run_scene(scene, quiet());
  CHECK(snapshots_finite(broken));
  CHECK(broken.summary.breaks > 0);
  check_final_equilibrium(scene, broken);
}

TEST_CASE("Hard: no gravity and no extension: nothing moves, nothing breaks", "[hard]") {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, false);
  scene.strength = strength_of(Criterion::elliptic, 50e6);
  scene.loading.total = 0;
  const SteppingMethod method = GENERATE(SteppingMethod::event, SteppingMethod::fixed);
  scene.stepping = {method, 1e-3};
  const RunResult result = run_scene(scene, quiet());
  CHECK(result.events.empty());
  CHECK(result.fragments.empty());
  REQUIRE(result.snapshots.size() == 1);
  for (double u : result.snapshots[0].displacement) CHECK(u == 0.0);
  for (double s : result.snapshots[0].node_stress) CHECK(s == 0.0);
  for (double f : result.snapshots[0].bond_failure_index) CHECK(f == 0.0);
}

TEST_CASE("Hard: lambda total 0 with a strength: gravity alone, no breaks when strong", "[hard]") {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, true);
  scene.strength = strength_of(Criterion::elliptic, 50e6);
  scene.loading.total = 0;
  const SteppingMethod method = GENERATE(SteppingMethod::event, SteppingMethod::fixed);
  scene.stepping = {method, 1e-3};
  const RunResult result = run_scene(scene, quiet());
  CHECK(result.events.empty());
  REQUIRE(result.snapshots.size() == 1);
  CHECK(result.snapshots[0].lambda == 0.0);
  CHECK(snapshots_finite(result));
  check_final_equilibrium(scene, result);
  // The walls are at rest: the wall nodes' x displacement is exactly zero.
  const Lattice lattice = build_lattice(scene.lattice);
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    if (lattice.on_face(n, Face::x_min) || lattice.on_face(n, Face::x_max)) {
      CHECK(result.snapshots[0].displacement[3 * n] == 0.0);
    }
  }
}

// ---------------------------------------------------------------------------------------
// 6. Drift of the updated factor

TEST_CASE(
    "Hard: after 2000 and 10000 downdates without refactorization the factor solves like a "
    "fresh one",
    "[hard]") {
  // 2000 breaks on 2178 nodes (6342 bonds); 10000 on 5930 nodes (17471 bonds), since a
  // lattice of 2000 nodes has too few bonds to lose 10000 and stay in one piece.
  const auto [length, target] = GENERATE(table<double, int>({{60.0, 2000}, {100.0, 10000}}));
  Scene scene = testing::box_scene(2, 1.0, {length, 0, length / 2}, true);
  scene.solver.refactor_every = 1000000;
  Model model = build_model(scene);
  INFO(model.lattice.node_count() << " nodes, " << target << " breaks");
  REQUIRE(model.lattice.node_count() > 2000);
  EquilibriumSolver solver(model, scene.solver);
  solver.affine_path();
  testing::break_random_bonds(model, solver, target, 7);
  CHECK(solver.counters().factor_updates == target);
  const AffinePath updated = solver.affine_path();
  CHECK(solver.counters().factorizations == 1);  // the comparison really used the updated factor
  EquilibriumSolver fresh(model, scene.solver);
  const AffinePath reference = fresh.affine_path();
  auto relative_difference = [](const Vector& a, const Vector& b) {
    return max_abs(a - b) / max_abs(b);
  };
  const double gravity = relative_difference(updated.gravity, reference.gravity);
  const double extension = relative_difference(updated.extension, reference.extension);
  INFO("relative differences: gravity " << gravity << ", extension " << extension);
  CHECK(gravity < 1e-8);
  CHECK(extension < 1e-8);
}

// ---------------------------------------------------------------------------------------
// 7. Ties

TEST_CASE("Hard: a tie of every horizontal bond breaks in bond-id order, the same every run",
          "[hard]") {
  // Rollers on top and base: u_x = lambda (x - c), u_z = 0 exactly, so every horizontal
  // bond reaches the tensile strength at lambda* = sigma0 / E together.
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, false);
  scene.faces[static_cast<int>(Face::z_max)] = FaceCondition::roller;
  scene.strength = strength_of(Criterion::tensile, 50e6);
  scene.loading.total = 6e-4;
  scene.stepping = {SteppingMethod::event, 0};
  const RunResult result = run_scene(scene, quiet());
  const Lattice lattice = build_lattice(scene.lattice);
  std::set<std::int64_t> horizontal;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    if (std::abs(lattice.bond_direction[b].z()) < 1e-12) horizontal.insert(b);
  }
  REQUIRE(result.events.size() >= horizontal.size());
  const std::int64_t first_cascade = result.events.front().cascade;
  std::set<std::int64_t> group;
  for (std::size_t k = 0; k < horizontal.size(); ++k) {
    const BreakEvent& e = result.events[k];
    INFO("event " << k << ": bond " << e.bond << ", f " << e.failure_index);
    CHECK(e.cascade == first_cascade);
    CHECK(e.lambda == Approx(5e-4).epsilon(1e-12));
    CHECK(e.failure_index == Approx(1.0).epsilon(1e-12));
    group.insert(e.bond);
    if (k == 0) continue;
    const BreakEvent& previous = result.events[k - 1];
    CHECK(e.lambda == previous.lambda);
    // Equal within rounding: the group breaks in bond-id order (docs/robustness.md).
    CHECK(e.bond > previous.bond);
  }
  CHECK(group == horizontal);
  INFO("breaks " << result.summary.breaks << ", parts held " << result.fragments.size());
  CHECK(snapshots_finite(result));
  check_final_equilibrium(scene, result);
  check_same_events(result, run_scene(scene, quiet()));
}

TEST_CASE("Hard: the smallest lattice shattered completely", "[hard]") {
  // Every part ends up held: nothing is left to solve, and the run must still finish.
  const int dim = GENERATE(2, 3);
  Scene scene = testing::box_scene(dim, 1.0, {2.0, 2.0, 2.0}, true);
  scene.strength = strength_of(Criterion::elliptic, 1.0);
  scene.loading.total = 1e-3;
  scene.stepping = {SteppingMethod::event, 0};
  const RunResult result = run_scene(scene, quiet());
  CHECK(snapshots_finite(result));
  CHECK(broken_set(result).size() == result.bond_count());
  check_final_equilibrium(scene, result);
}

TEST_CASE("Hard: an elastic scene whose pre-cuts isolate a node holds it", "[hard]") {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, true);
  scene.loading.total = 1e-3;
  const Lattice lattice = build_lattice(scene.lattice);
  const std::int64_t centre = node_nearest(lattice, {10.0, 0, 5.0});
  scene.precuts = hexagon_around(lattice.positions[centre], 1.0);
  const RunResult result = run_scene(scene, quiet());
  REQUIRE(result.fragments.size() == 1);
  CHECK(result.fragments[0].nodes == 1);
  CHECK(snapshots_finite(result));
  check_final_equilibrium(scene, result);
}

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
  // Whether a scene makes the active-set iteration revisit a set depends on rounding: a
  // single scene found by a search cycled with some BLAS kernels and not with others. So
  // the test takes the first scene of a fixed family that cycles. The family cycles
  // because of the breaks (kept intact, 1 of its first 300 scenes cycles). Measured with
  // seven BLAS kernels (OpenBLAS SkylakeX, Haswell, Zen, SandyBridge, Nehalem, Prescott;
  // reference BLAS), built with and without -march=native: 39 to 50 % of its scenes cycle,
  // the first within the first 9, and never more than 11 in a row do not; 40 scenes leave
  // practically no chance of finding none.
  std::mt19937 random(1105);
  Scene scene;
  RunResult result;
  int trial = 0;
  do {
    scene = pressed_triangles(random);
    result = run_scene(scene, quiet());
  } while (result.summary.contact_cycles == 0 && ++trial < 40);
  INFO("scene " << trial);
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

TEST_CASE("Hard: a cascade of thousands of bonds at one lambda finishes in equilibrium", "[hard]") {
  // A crust far too weak for its own weight: the whole collapse is one cascade at
  // lambda = 0. Each break stores one event and nothing else (docs/robustness.md).
  Scene scene = testing::box_scene(2, 1.0, {60.0, 0, 30.0}, true);
  scene.strength = strength_of(Criterion::elliptic, 2e4);
  scene.strength->friction_angle = 30.0;
  scene.loading.total = 0;
  const RunResult result = run_scene(scene, quiet());
  CHECK(result.summary.breaks > 1000);
  CHECK(static_cast<std::int64_t>(result.events.size()) == result.summary.breaks);
  std::set<std::int64_t> cascades;
  for (const BreakEvent& e : result.events) {
    CHECK(e.lambda == 0.0);
    cascades.insert(e.cascade);
  }
  CHECK(cascades.size() == 1);
  CHECK(snapshots_finite(result));
  check_final_equilibrium(scene, result);
}

TEST_CASE("Hard: updates fall back to a fresh factorization when the residual check fails",
          "[hard]") {
  // Layers with E ratio 1e4. Measured: after 500 downdates the updated factor still
  // solves to a relative residual of about 1e-15, like a fresh one, so accuracy never
  // drops here; a tolerance below what any factor reaches forces the fallback.
  Scene scene = testing::box_scene(2, 1.0, {40.0, 0, 20.0}, true);
  Layer stiff;
  stiff.z_min = 0;
  stiff.z_max = 10;
  stiff.material = testing::paper_material();
  stiff.material.young = 100e9 * 1e4;
  scene.layers.push_back(stiff);
  const double tolerance = GENERATE(1e-12, 1e-18);
  scene.solver.tolerance = tolerance;
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  solver.affine_path();
  testing::break_random_bonds(model, solver, 50, 3);
  REQUIRE(solver.counters().factorizations == 1);
  if (tolerance > 1e-15) {
    const Vector u = solver.checked_solve(1e-3);  // the updated factor suffices
    CHECK(solver.counters().factorizations == 1);
    CHECK(max_abs(model.residual(u, 1e-3)) / solver.load_scale(1e-3) <= tolerance);
  } else {
    CHECK_THROWS_WITH(solver.checked_solve(1e-3), Catch::Contains("after a fresh factorization"));
    CHECK(solver.counters().factorizations == 2);  // it did fall back once
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

}  // namespace

TEST_CASE("Hard: 130 random scenes of every kind end in equilibrium, part by part", "[hard]") {
  // Found by this search, fixed in docs/model.md and docs/robustness.md: event-driven
  // contact left contacts tied with a switch penetrating for the rest of the path (trials
  // 13, 15, 18, 60, 75: residuals up to 0.2 of the load); the large-kinematics route did
  // not settle contacts at the end (86); and the singular-stiffness safety net held a
  // node along an axis in which its part was supported, so the walls pushed against the
  // hold (126: 0.17 of the load). 600 scenes pass with three BLAS kernels.
  for (int trial = 0; trial < 130; ++trial) {
    const Scene scene = random_scene(trial);
    INFO("trial " << trial);
    RunResult result;
    REQUIRE_NOTHROW(result = run_scene(scene, quiet()));
    CHECK(snapshots_finite(result));
    CHECK(balance(final_state(scene, result)).relative_residual <= 1e-9);
  }
}

TEST_CASE("Hard: 60 random scenes with contact and many cuts end in equilibrium", "[hard]") {
  // Found by this search (scenes 75 and 119): at lambda = 0 without gravity every contact
  // sits at dn = 0, and contacts whose rate was rounding (either sign) switched back and
  // forth at one lambda until the cycle guard stopped switching there, leaving others
  // penetrating for the rest of the path (0.26 and 0.002 of the load). 800 scenes pass.
  for (int trial = 70; trial < 130; ++trial) {
    const Scene scene = random_contact_scene(trial);
    INFO("trial " << trial);
    RunResult result;
    REQUIRE_NOTHROW(result = run_scene(scene, quiet()));
    CHECK(snapshots_finite(result));
    CHECK(balance(final_state(scene, result)).relative_residual <= 1e-9);
  }
}

