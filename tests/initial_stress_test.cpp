// The initial lithostatic stress (gravity.initial_stress = "lithostatic", docs/model.md,
// "Initial stress"): a random lattice whose bonds carry their facets' share of
// sigma0 = -rho g depth I stands under its weight without moving, its walls carry the
// lithostatic thrust, its response to extension is the unstressed body's (linearity), and
// a broken bond under compression stays a pre-compressed contact. With stress_ratio K the
// horizontal stress is K sigma0_v: the same balance, with the bonds sheared by it.
#include <catch2/catch.hpp>
#include <cmath>

#include "hard_case_checks.h"
#include "latfrac/base/error.h"
#include "latfrac/fracture/event_source.h"
#include "latfrac/mechanics/node_stress.h"
#include "latfrac/mechanics/random_calibration.h"
#include "latfrac/solvers/equilibrium.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

Scene lithostatic_box(int dim, bool lithostatic, double ratio = 1) {
  Scene scene = dim == 2 ? box_scene(2, 500.0, {12e3, 0, 6e3}, true)
                         : box_scene(3, 1000.0, {8e3, 5e3, 5e3}, true);
  scene.lattice.kind = LatticeKind::random;
  scene.lattice.seed = 11;
  scene.gravity->lithostatic = lithostatic;
  scene.gravity->stress_ratio = ratio;
  return scene;
}

// A scene's model and the solver that owns its run.
struct Started {
  explicit Started(Scene s)
      : scene(std::move(s)), model(build_model(scene)), solver(model, scene.solver) {}
  Scene scene;
  Model model;
  EquilibriumSolver solver;
};

// The same box started unstressed and prestressed (K = ratio).
struct Starts {
  Starts(int dim, double ratio)
      : elastic(lithostatic_box(dim, false)), stressed(lithostatic_box(dim, true, ratio)) {}
  Started elastic, stressed;
};

}  // namespace

TEST_CASE("Lithostatic start: the body stands still, and its walls carry K rho g H^2 / 2",
          "[initial_stress][random]") {
  const int dim = GENERATE(2, 3);
  // K = 1, the isotropic lithostatic state; K = 0.4, an Andersonian one (sigma1 vertical).
  const double ratio = GENERATE(1.0, 0.4);
  Starts starts(dim, ratio);
  const Scene& scene = starts.stressed.scene;
  const Model& elastic = starts.elastic.model;
  const Model& model = starts.stressed.model;
  REQUIRE(model.has_prestress());
  const Vector u_elastic =
      elastic.full_displacement(starts.elastic.solver.affine_path().at(0.0), 0.0);
  const Vector u = model.full_displacement(starts.stressed.solver.affine_path().at(0.0), 0.0);
  // The facets' forces sum to the divergence of sigma0 over each cell (the divergence
  // theorem, exact for a linear field on a polygon or polyhedron): rho g V upwards, the
  // node's weight (the horizontal part K sigma0_v does not vary along x). Nothing moves,
  // up to rounding.
  INFO(dim << "-D, K = " << ratio << ": largest displacement " << max_abs(u)
           << " m, unstressed start " << max_abs(u_elastic) << " m");
  CHECK(max_abs(u) < 1e-9 * max_abs(u_elastic));
  // The supports: the base carries the weight, each wall the thrust K rho g H^2 / 2 per
  // unit width, where the unstressed start gives nu / (1 - nu) of rho g H^2 / 2.
  const Lattice& lattice = model.lattice;
  const double rho_g = scene.material.density * scene.gravity->g, nu = scene.material.poisson;
  const double height = lattice.extent.z(), width = dim == 3 ? lattice.extent.y() : 1.0;
  const double volume = lattice.extent.x() * height * width;
  for (const bool prestressed : {false, true}) {
    const Model& m = prestressed ? model : elastic;
    const Vector reactions = m.reactions(prestressed ? u : u_elastic);
    double base = 0, wall = 0;
    for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
      if (lattice.on_face(n, Face::z_min)) base += reactions[n * dim + dim - 1];
      if (lattice.on_face(n, Face::x_min)) wall += reactions[n * dim];
    }
    INFO((prestressed ? "lithostatic" : "unstressed")
         << " start: base " << base << " N, wall " << wall << " N");
    CHECK(base == Approx(rho_g * volume).epsilon(1e-9));
    const double thrust = rho_g * height * height / 2 * width;
    if (prestressed) {
      // Each wall piece takes sigma0 at its centroid times its area: the integral of the
      // linear sigma0 over the wall, exactly.
      CHECK(wall == Approx(ratio * thrust).epsilon(1e-9));
    } else {
      // About K0 = nu / (1 - nu) = 0.25 of it for nu = 0.2 (0.22 on this 2-D box, whose
      // random lattice is a few cells across), far from the lithostatic thrust.
      CHECK(wall == Approx(nu / (1 - nu) * thrust).epsilon(0.2));
    }
  }
  // In the middle band, the node stress reads sigma0 = sigma0_v diag(K, K, 1) (the scatter
  // of a random lattice's node stresses is about the cells' centroid offsets times rho g);
  // the 2-D out-of-plane sigma_yy is K sigma0_v too.
  const std::vector<double> stress = node_stresses(model, u);
  double xx = 0, yy = 0, zz = 0, xz = 0, expected = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3& p = lattice.positions[n];
    if (p.z() < 0.3 * height || p.z() > 0.7 * height) continue;
    if (std::abs(p.x() - lattice.extent.x() / 2) > 0.3 * lattice.extent.x()) continue;
    xx += stress[6 * n];
    yy += stress[6 * n + 1];
    zz += stress[6 * n + 2];
    xz += stress[6 * n + 4];
    expected += model.node_initial_stress[n];
    CHECK(model.node_initial_stress[n] == Approx(-rho_g * (height - p.z())).epsilon(1e-12));
  }
  CHECK(xx / expected == Approx(ratio).epsilon(0.01));
  CHECK(yy / expected == Approx(ratio).epsilon(0.01));
  CHECK(zz / expected == Approx(1).epsilon(0.01));
  CHECK(std::abs(xz / expected) < 0.01);
}

TEST_CASE("Lithostatic start: extension adds to sigma0 what it adds to the unstressed body",
          "[initial_stress][random]") {
  // The springs are linear: the prestress is a constant the response to extension does
  // not see, as long as every bond is intact.
  const int dim = GENERATE(2, 3);
  const double ratio = GENERATE(1.0, 0.4);
  Starts starts(dim, ratio);
  const Model& elastic = starts.elastic.model;
  const Model& model = starts.stressed.model;
  const AffinePath elastic_path = starts.elastic.solver.affine_path();
  const AffinePath path = starts.stressed.solver.affine_path();
  const double lambda = 1e-3;
  const Vector change_elastic = elastic_path.at(lambda) - elastic_path.at(0.0);
  const Vector change = path.at(lambda) - path.at(0.0);
  CHECK(max_abs(change - change_elastic) < 1e-9 * max_abs(change_elastic));
  const std::vector<double> s1 =
      node_stresses(model, model.full_displacement(path.at(lambda), lambda));
  const std::vector<double> s0 = node_stresses(model, model.full_displacement(path.at(0.0), 0.0));
  const std::vector<double> e1 =
      node_stresses(elastic, elastic.full_displacement(elastic_path.at(lambda), lambda));
  const std::vector<double> e0 =
      node_stresses(elastic, elastic.full_displacement(elastic_path.at(0.0), 0.0));
  double largest = 0, worst = 0;
  for (std::size_t k = 0; k < s1.size(); ++k) {
    largest = std::max(largest, std::abs(e1[k] - e0[k]));
    worst = std::max(worst, std::abs((s1[k] - s0[k]) - (e1[k] - e0[k])));
  }
  INFO("largest stress change " << largest << " Pa, difference " << worst << " Pa");
  CHECK(worst < 1e-8 * largest);
  // And the path's slope of the node stresses is the same (what the crossings read).
  const std::vector<double> rate = node_stress_rates(model, full_path(model, path).per_lambda);
  const std::vector<double> elastic_rate =
      node_stress_rates(elastic, full_path(elastic, elastic_path).per_lambda);
  double rate_scale = 0, rate_worst = 0;
  for (std::size_t k = 0; k < rate.size(); ++k) {
    rate_scale = std::max(rate_scale, std::abs(elastic_rate[k]));
    rate_worst = std::max(rate_worst, std::abs(rate[k] - elastic_rate[k]));
  }
  CHECK(rate_worst < 1e-9 * rate_scale);
}

TEST_CASE("Lithostatic start with K: each bond carries its facet's traction sigma0 n0 A",
          "[initial_stress][random]") {
  // sigma0 = sigma0_v diag(K, K, 1) is not isotropic: a facet inclined to the axes gets a
  // traction with a part along the facet, which the bond's shear spring carries.
  const int dim = GENERATE(2, 3);
  const double ratio = 0.4;
  const Scene scene = lithostatic_box(dim, true, ratio);
  const Model model = build_model(scene);
  const Lattice& lattice = model.lattice;
  const Vector u = Vector::Zero(model.dofs().dof_count());
  const double rho_g = scene.material.density * scene.gravity->g;
  double worst = 0, largest_shear = 0;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const double vertical = -rho_g * (lattice.extent.z() - lattice.bond_facet_centroid[b].z());
    const Vec3& n = lattice.bond_direction[b];
    const double area = lattice.bond_facet_area[b];
    const Vec3 traction = area * vertical * Vec3(ratio * n.x(), ratio * n.y(), n.z());
    const Vec3 t = model.bond_tension(u, b);
    worst = std::max(worst, (t - traction).norm() / std::max(traction.norm(), 1.0));
    largest_shear =
        std::max(largest_shear, (t - t.dot(n) * n).norm() / std::max(std::abs(t.dot(n)), 1.0));
  }
  INFO(dim << "-D: largest relative difference " << worst << ", largest shear / normal "
           << largest_shear);
  CHECK(worst < 1e-12);
  // (1 - K) / 2 over (1 + K) / 2 at 45 degrees: bonds are sheared by about 0.43 of their
  // normal force.
  CHECK(largest_shear > 0.4);
}

TEST_CASE("Lithostatic start with K: bonds without shear springs are refused unless K = 1",
          "[initial_stress][random]") {
  // A random lattice at its largest nu has ks = 0 (docs/model.md, section 2): its bonds
  // carry the isotropic state along n0, but not the shear part of an anisotropic one.
  const int dim = GENERATE(2, 3);
  Scene scene = lithostatic_box(dim, true, 0.4);
  scene.material.poisson = random_lattice_max_poisson(dim);
  CHECK_THROWS_AS(build_model(scene), InputError);
  scene.gravity->stress_ratio = 1;
  const Model model = build_model(scene);
  const Vector u = Vector::Zero(model.dofs().dof_count());
  REQUIRE(model.shear_stiffness[0] == 0);
  double worst = 0;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    const Vec3& n = model.lattice.bond_direction[b];
    const Vec3 t = model.bond_tension(u, b);
    worst = std::max(worst, (t - t.dot(n) * n).norm() / std::max(std::abs(t.dot(n)), 1.0));
  }
  INFO(dim << "-D: largest shear / normal at rest " << worst);
  CHECK(worst < 1e-12);
}

TEST_CASE("Lithostatic start: a broken bond under compression stays a pre-compressed contact",
          "[initial_stress][random][contact]") {
  Scene scene = lithostatic_box(2, true);
  scene.contact = Contact{};
  Model model = build_model(scene);
  const Vector u = Vector::Zero(model.dofs().dof_count());
  // An interior bond: at rest it carries sigma0(c_b) A_b along n0 (compression).
  const Lattice& lattice = model.lattice;
  std::int64_t bond = -1;
  for (std::int64_t b = 0; b < lattice.bond_count() && bond < 0; ++b)
    if (lattice.bond_facet_centroid[b].z() < 0.5 * lattice.extent.z()) bond = b;
  REQUIRE(bond >= 0);
  const double sigma0 = -scene.material.density * scene.gravity->g *
                        (lattice.extent.z() - lattice.bond_facet_centroid[bond].z());
  const Vec3& n0 = lattice.bond_direction[bond];
  const Vec3 intact = model.bond_tension(u, bond);
  CHECK(intact.dot(n0) == Approx(sigma0 * lattice.bond_facet_area[bond]).epsilon(1e-12));
  CHECK((intact - intact.dot(n0) * n0).norm() < 1e-9 * std::abs(intact.dot(n0)));
  // Broken into a contact, it settles closed (its faces still pressed together) and
  // carries the same normal force.
  ModelEditor editor(model);
  editor.set_state(bond, PairState::open);
  const PairTarget target = model.contact_law()->settled_state(model.springs(bond), PairState::open,
                                                               model.bond_displacement(u, bond));
  CHECK(target.state == PairState::closed);
  editor.set_state(bond, PairState::closed);
  CHECK(model.bond_tension(u, bond).dot(n0) == Approx(intact.dot(n0)).epsilon(1e-12));
  // It opens where its faces have moved apart by the prestretch, -t0 / kn.
  const double opening = -sigma0 * lattice.bond_facet_area[bond] / model.normal_stiffness[bond];
  CHECK(model.prestretch[bond].dot(n0) == Approx(opening).epsilon(1e-12));
  const PairSwitch change = model.contact_law()->next_switch(model.springs(bond), PairState::closed,
                                                             model.bond_displacement(u, bond), n0,
                                                             0.0, 10 * opening, false);
  REQUIRE(change.found());
  CHECK(change.to == PairState::open);
  CHECK(change.s == Approx(opening).epsilon(1e-9));
}

TEST_CASE("Lithostatic start: event-driven runs end in equilibrium, nothing breaks at rest",
          "[initial_stress][random][hard]") {
  // Friction 0: the final state is rebuilt from the snapshot alone (final_state.h) and
  // checked; friction 0.6: the run completes with finite results.
  const double friction = GENERATE(0.0, 0.6);
  Scene scene = lithostatic_box(2, true);
  scene.strength = strength_of(Criterion::elliptic, 5e6, 30.0);
  scene.strength->tau0_factor = 2;
  scene.strength->bond_stress = BondStress::tensor;
  scene.strength->internal_friction = 0.6;
  scene.contact = Contact{true, friction};
  scene.loading.total = 2e-3;
  scene.loading.basal_discontinuity = 6e3;
  scene.output.snapshots = {2e-3};
  const RunResult result = run_scene(scene, quiet());
  INFO("friction " << friction << ": " << result.events.size() << " breaks");
  REQUIRE(!result.events.empty());
  CHECK(snapshots_finite(result));
  // The body starts where it stands: the first break needs some extension.
  CHECK(result.events.front().lambda > 0);
  if (friction == 0) check_final_equilibrium(scene, result);
}

TEST_CASE(
    "Overburden: the body stands still under p0 on its top, the supports carry it, "
    "and every node reads sigma0",
    "[initial_stress][random]") {
  const int dim = GENERATE(2, 3);
  const double ratio = GENERATE(1.0, 0.4);
  const double p0 = 2e8;  // Pa: about 7.5 km of rock above the top
  for (const double g : {0.0, 9.81}) {
    Scene scene = lithostatic_box(dim, true, ratio);
    scene.gravity->g = g;
    scene.gravity->overburden = p0;
    Started started(scene);
    const Model& model = started.model;
    const Lattice& lattice = model.lattice;
    const Vector u = model.full_displacement(started.solver.affine_path().at(0.0), 0.0);
    const double height = lattice.extent.z(), width = dim == 3 ? lattice.extent.y() : 1.0;
    const double top_area = lattice.extent.x() * width;
    INFO(dim << "-D, K = " << ratio << ", g = " << g << ": largest displacement " << max_abs(u)
             << " m");
    // The top's pressure meets the uniform part of the initial stress on every top cell:
    // nothing moves (p0 H / E is metres here).
    CHECK(max_abs(u) < 1e-9 * p0 * height / scene.material.young);
    // The base carries the weight and the rock above; each wall K times the vertical
    // stress integrated over its height.
    const Vector reactions = model.reactions(u);
    double base = 0, wall = 0;
    for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
      if (lattice.on_face(n, Face::z_min)) base += reactions[n * dim + dim - 1];
      if (lattice.on_face(n, Face::x_min)) wall += reactions[n * dim];
    }
    const double rho_g = scene.material.density * g;
    CHECK(base == Approx(rho_g * top_area * height + p0 * top_area).epsilon(1e-9));
    CHECK(wall ==
          Approx(ratio * (p0 * height + rho_g * height * height / 2) * width).epsilon(1e-9));
    if (g != 0) continue;
    // Without gravity sigma0 is uniform, -p0 diag(K, K, 1): every node reads it, the face
    // nodes too (the top ones through the pressure on their face pieces, at the pieces'
    // centroids; the others through their supports).
    const std::vector<double> stress = node_stresses(model, u);
    double worst = 0;
    for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
      const double expected[6] = {-ratio * p0, -ratio * p0, -p0, 0, 0, 0};
      for (int k = 0; k < 6; ++k)
        worst = std::max(worst, std::abs(stress[6 * n + k] - expected[k]));
    }
    INFO("worst node stress error " << worst << " Pa");
    CHECK(worst < 1e-9 * p0);
  }
}

TEST_CASE("Overburden: a scene built in code without the lithostatic start is refused",
          "[initial_stress]") {
  // Without the bonds' initial stress nothing would balance the top's pressure: the
  // reader refuses such a file, and so does the model builder.
  Scene scene = lithostatic_box(2, false);
  scene.gravity->overburden = 1e8;
  CHECK_THROWS_WITH(build_model(scene), Catch::Contains("gravity.overburden"));
}
