// The paper's scenes against hand computations and the lattice's geometry: why gravity
// alone breaks the elliptic crust for m < 2.7, how the two bond-stress readings see
// lithostatic confinement, and the 2-D lattice's crack path in Fig. 4a
// (docs/validation.md). Each test loads a shipped problem file.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "latfrac/solvers/equilibrium.h"
#include "latfrac/analysis/fault_analysis.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/mechanics/model.h"
#include "latfrac/mechanics/node_stress.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/scene/run.h"
#include "latfrac/scene/model_builder.h"
#include "lithostatic_check.h"

using namespace latfrac;

namespace {

std::string problem(const char* name) {
  return (std::filesystem::path(__FILE__).parent_path().parent_path() / "problems" / name)
      .string();
}

// The gravity-loaded state (lambda = 0) of a scene and every bond's failure index in it.
struct GravityState {
  Scene scene;
  Model model;
  std::vector<double> f;
  double surface = 0;  // z of the top row plus half a row pitch, m
};

GravityState gravity_state(const std::string& path, const std::vector<std::string>& overrides) {
  GravityState s{read_problem_file(path, overrides), {}, {}, 0};
  s.model = build_model(s.scene);
  EquilibriumSolver solver(s.model, s.scene.solver);
  const AffinePath path_ = solver.affine_path();
  const Vector u = s.model.full_displacement(path_.gravity, 0.0);
  const FailureEvaluator evaluator(*s.scene.strength, s.model);
  std::vector<BreakMode> modes;
  evaluator.evaluate(s.model, u, s.f, modes);
  s.surface = testing::surface_height(s.model.lattice);
  return s;
}

// Interior: at least a quarter of the length from either wall, away from the pre-cut.
bool interior(const Model& model, std::int64_t b, double length) {
  const Bond& bond = model.lattice.bonds[b];
  const double x = 0.5 * (model.lattice.positions[bond.i].x() + model.lattice.positions[bond.j].x());
  return x > 0.25 * length && x < 0.4 * length;
}

// Uniaxial-strain (walls held) vertical strain at depth d below the surface.
double uniaxial_eps_zz(const Material& m, double g, double depth) {
  const double nu = m.poisson;
  const double sigma_zz = -m.density * g * depth;
  return sigma_zz * (1 + nu) * (1 - 2 * nu) / (m.young * (1 - nu));
}

}  // namespace

TEST_CASE("Gravity alone: the deep diagonals' elliptic f matches the hand value: m = 2 breaks, m = 3 not",
          "[validation]") {
  // With bond strains and the walls held, a diagonal bond at 60 degrees sees eps_n =
  // (3/4) eps_zz < 0 and the shear strain gamma = (sqrt3 / 4) |eps_zz|, so
  // f = (G gamma / tau0)^2 with tau0 = m sigma0 (1 + sin psi) / (2 cos psi). At the base of
  // the 30 km crust this is 7.1 for m = 1: the crust survives gravity only for m above
  // sqrt(7.1) = 2.7.
  GravityState s = gravity_state(problem("fig6-elliptic-graben-2d.toml"),
                                 {"lattice.spacing=1000", "strength.tau0_factor=1"});
  const Material& material = s.scene.material;
  const double G = material.young / (2 * (1 + material.poisson));
  const double psi = *s.scene.strength->friction_angle * M_PI / 180;
  const double tau0 = s.scene.strength->sigma0 * (1 + std::sin(psi)) / (2 * std::cos(psi));
  const Lattice& lattice = s.model.lattice;
  double checked = 0, largest = 0;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    largest = std::max(largest, s.f[b]);
    if (!interior(s.model, b, s.scene.lattice.size[0]) || std::abs(lattice.bond_direction[b].z()) < 0.5)
      continue;
    const Bond& bond = lattice.bonds[b];
    const double depth =
        s.surface - 0.5 * (lattice.positions[bond.i].z() + lattice.positions[bond.j].z());
    const double gamma =
        std::sqrt(3.0) / 4 * std::abs(uniaxial_eps_zz(material, s.scene.gravity->g, depth));
    const double hand = std::pow(G * gamma / tau0, 2);
    if (hand < 1) continue;  // the shallow bonds: relative error of a small number
    // tau within 2.5 % (the lithostatic tests hold sigma_zz to 2 %; the discrete rows add
    // an offset of about a quarter row pitch in depth), so f = tau^2 within 5 %.
    INFO("bond " << b << " at depth " << depth << " m");
    CHECK(s.f[b] == Approx(hand).epsilon(0.05));
    ++checked;
  }
  CHECK(checked > 20);
  // f scales as 1 / m^2: m = 2 leaves bonds above 1, m = 3 none.
  INFO("largest f at m = 1: " << largest);
  CHECK(largest / 4 > 1);
  CHECK(largest / 9 < 1);
}

TEST_CASE("Bond strains miss the lithostatic confinement that the resolved tensor carries",
          "[validation]") {
  // Walls held under gravity: eps_xx = 0, so a horizontal bond's own strain gives
  // sigma_n = E eps_n = 0 at every depth, while the continuum carries
  // sigma_xx = nu / (1 - nu) sigma_zz. The resolved tensor (bond_stress = "tensor") sees it.
  GravityState s = gravity_state(problem("fig4a-tensile-2d.toml"), {"lattice.spacing=2000"});
  const Material& material = s.scene.material;
  const Lattice& lattice = s.model.lattice;
  EquilibriumSolver solver(s.model, s.scene.solver);
  const Vector u = s.model.full_displacement(solver.affine_path().gravity, 0.0);
  const std::vector<double> node_stress = node_stresses(s.model, u);
  int checked = 0;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Vec3& n = lattice.bond_direction[b];
    if (!interior(s.model, b, s.scene.lattice.size[0]) || std::abs(n.z()) > 1e-9) continue;
    const double z = lattice.positions[lattice.bonds[b].i].z();
    const double depth = s.surface - z;
    if (depth < 4 * lattice.spacing || z < 4 * lattice.spacing) continue;  // off top and base
    const double sigma_zz = -material.density * s.scene.gravity->g * depth;
    const double sigma_xx = material.poisson / (1 - material.poisson) * sigma_zz;
    const double from_strain =
        material.young * n.dot(s.model.bond_displacement(u, b)) / lattice.bond_length[b];
    const double from_tensor = resolve_on(bond_stress_tensor(node_stress, lattice.bonds[b]), n).normal;
    INFO("bond " << b << " at depth " << depth << " m: sigma_xx " << sigma_xx);
    CHECK(std::abs(from_strain) < 0.02 * std::abs(sigma_xx));
    CHECK(from_tensor == Approx(sigma_xx).epsilon(0.03));
    ++checked;
  }
  CHECK(checked > 10);
}

TEST_CASE("Fig. 4a in 2-D with bond strains: the first crack follows the 60 degree rows",
          "[validation]") {
  // What the bond-strain reading gives instead of the paper's vertical fault
  // (docs/validation.md, effect 4):
  // by lambda = 5e-4 the tensile crack has left the pre-cut tip along both 60 degree rows of
  // the triangular lattice down to the base. Event-driven, so no increment decides it.
  const Scene scene = read_problem_file(
      problem("fig4a-tensile-2d.toml"),
      {"strength.bond_stress=strain", "stepping.method=event", "loading.total=5e-4",
       "output.snapshots=[5e-4]"});
  const RunResult result = run_scene(scene, {});
  const FaultReport report = analyze_faults(result);
  std::vector<Fault> faults;
  for (const Fault& f : report.faults)
    if (!f.diffuse) faults.push_back(f);
  REQUIRE(faults.size() == 2);
  for (const Fault& f : faults) {
    CHECK(f.dip_deg == Approx(60).margin(2));
    CHECK(f.extent > 20e3);  // from the pre-cut tip (25 km) most of the way to the base
  }
  CHECK(faults[0].dip_direction == -faults[1].dip_direction);
}

TEST_CASE("Fig. 4a as shipped: tensile faults are vertical and the pre-cut's severs the crust",
          "[validation]") {
  // The shipped scene: fixed ds = 1e-3 to lambda = 0.04, the critical-plane reading
  // (docs/validation.md). The paper: "the entire crust is severed by a single vertical
  // fault". Here every cluster of broken bonds is a clean fault within 10 degrees of
  // vertical, none diffuse, and the one below the pre-cut runs from its tip (25 km) to the
  // base. Two more vertical faults open near the walls (docs/validation.md says why).
  const Scene scene = read_problem_file(problem("fig4a-tensile-2d.toml"), {});
  const RunResult result = run_scene(scene, {});
  const FaultReport report = analyze_faults(result);
  REQUIRE(!report.faults.empty());
  int central = 0;
  for (const Fault& f : report.faults) {
    INFO("fault at x = " << f.centroid[0] << " m, dip " << f.dip_deg << " deg, "
                         << f.bonds << " bonds");
    CHECK_FALSE(f.diffuse);
    CHECK(f.alpha_deg < 10);
    CHECK(f.tensile_share == 1.0);
    if (std::abs(f.centroid[0] - 30e3) < 2e3) {
      ++central;
      CHECK(f.extent > 23e3);  // the 25 km below the pre-cut, within a spacing or two
      CHECK(f.centroid[2] < 14e3);
    }
  }
  CHECK(central == 1);
}

TEST_CASE("Fig. 6 as shipped, with contact: a graben of two faults from the surface, one from the pre-cut",
          "[validation]") {
  // The paper's Fig. 6: a graben, two inclined faults dipping towards each other, the
  // block between them subsided. The shipped scene (contact, fixed ds = 1e-3) forms one
  // (docs/validation.md): the faults' dips are the triangular lattice's 60 degree rows,
  // which this test does not take as agreement with Coulomb; it checks the structure.
  const Scene scene = read_problem_file(problem("fig6-elliptic-graben-2d.toml"), {});
  REQUIRE(scene.contact);
  const RunResult result = run_scene(scene, {});
  const FaultReport report = analyze_faults(result);
  REQUIRE(report.graben);
  const Graben& graben = report.grabens[*report.graben];
  const Fault& left = report.faults[graben.left_fault];
  const Fault& right = report.faults[graben.right_fault];
  CHECK(left.dip_direction == +1);
  CHECK(right.dip_direction == -1);
  for (const Fault* f : {&left, &right}) {
    CHECK_FALSE(f->diffuse);
    CHECK(f->extent > 20e3);  // through most of the 30 km crust
    CHECK(f->dip_deg > 45);
    CHECK(f->dip_deg < 75);
  }
  CHECK(graben.surface_subsidence > 0);  // the block between them went down
  // The pre-cut's fault is one of the two, and no cluster is a shattered region.
  REQUIRE(report.precut_fault);
  CHECK((*report.precut_fault == graben.left_fault || *report.precut_fault == graben.right_fault));
  for (const Fault& f : report.faults) CHECK_FALSE(f.diffuse);
  // Without contact the same scene shatters: most of the section in diffuse clusters.
  const Scene without = read_problem_file(problem("fig6-elliptic-graben-2d.toml"),
                                          {"contact.enabled=false", "loading.total=2e-3",
                                           "output.snapshots=[2e-3]"});
  const FaultReport shattered = analyze_faults(run_scene(without, {}));
  std::int64_t diffuse = 0;
  for (const Fault& f : shattered.faults) diffuse += f.diffuse ? f.bonds : 0;
  CHECK(diffuse > 3000);
}
