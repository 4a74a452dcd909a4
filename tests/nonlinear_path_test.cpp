// The large-kinematics law (tangent, rigid rotation) and the CVODE path: on an affine scene
// it finds the closed-form first break, on a large-kinematics scene it ends in equilibrium.
#include "latfrac/solvers/nonlinear_path.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "latfrac/mechanics/bond_law.h"
#include "latfrac/criteria/crossing.h"
#include "latfrac/solvers/equilibrium.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "criterion_calls.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

constexpr double pi = 3.14159265358979323846;

// A bond law called with a reference geometry and its springs, as these tests write it.
Vec3 tension_of(const BondLaw& law, const BondReference& r, const Vec3& du, double kn, double ks) {
  return law.tension({r.direction, r.length, kn, ks}, PairState::intact, du);
}
Mat3 tangent_of(const BondLaw& law, const BondReference& r, const Vec3& du, double kn, double ks) {
  return law.tangent({r.direction, r.length, kn, ks}, PairState::intact, du);
}
Mat3 jacobian_of(const BondLaw& law, const BondReference& r, const Vec3& du, double kn, double ks) {
  return law.jacobian({r.direction, r.length, kn, ks}, PairState::intact, du);
}

Mat3 central_difference_tangent(const BondLaw& law, const BondReference& reference, const Vec3& du,
                                double kn, double ks, double step) {
  Mat3 tangent;
  for (int k = 0; k < 3; ++k) {
    Vec3 plus = du, minus = du;
    plus[k] += step;
    minus[k] -= step;
    tangent.col(k) =
        (tension_of(law, reference, plus, kn, ks) - tension_of(law, reference, minus, kn, ks)) / (2 * step);
  }
  return tangent;
}

Scene strength_scene(bool large_kinematics, Criterion criterion, double sigma0) {
  Scene scene = testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true);
  scene.strength = testing::strength_of(criterion, sigma0);
  scene.large_kinematics = large_kinematics;
  return scene;
}

// The closed-form first break on the affine path: the smallest first_crossing over the
// intact bonds, and every bond crossing within 1e-12 relative of it (a tie: a mirror pair
// crosses at lambdas that differ by rounding, and the largest f then decides, as in
// docs/robustness.md).
struct FirstBreak {
  double lambda = std::numeric_limits<double>::infinity();
  std::vector<std::int64_t> tied;
  bool contains(std::int64_t bond) const {
    return std::find(tied.begin(), tied.end(), bond) != tied.end();
  }
};

FirstBreak closed_form_first_break(const Model& model, const AffinePath& path,
                                   const CriterionParameters& criterion, double to) {
  const Vector gravity = model.full_displacement(path.gravity, 0.0);
  const Vector extension = model.full_displacement(path.extension, 1.0) -
                           model.full_displacement(Vector::Zero(path.extension.size()), 0.0);
  std::vector<double> crossing(model.lattice.bond_count(), std::numeric_limits<double>::infinity());
  FirstBreak first;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (!model.intact(b)) continue;
    const Vec3& n0 = model.lattice.bond_direction[b];
    const double length = model.lattice.bond_length[b];
    const Vec3 du_g = model.bond_displacement(gravity, b),
               du_e = model.bond_displacement(extension, b);
    const double dn_g = n0.dot(du_g), dn_e = n0.dot(du_e);
    AffineBondStress stress;
    stress.normal0 = model.bond_young[b] / length * dn_g;
    stress.normal1 = model.bond_young[b] / length * dn_e;
    stress.shear0 = model.bond_shear_modulus[b] / length * (du_g - dn_g * n0);
    stress.shear1 = model.bond_shear_modulus[b] / length * (du_e - dn_e * n0);
    crossing[b] = first_crossing(criterion.criterion, stress, model.bond_sigma0[b],
                                 model.bond_tau0[b], 0.0, to);
    first.lambda = std::min(first.lambda, crossing[b]);
  }
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (crossing[b] <= first.lambda * (1 + 1e-12)) first.tied.push_back(b);
  }
  return first;
}

}  // namespace

TEST_CASE("The large-kinematics Jacobian matches central differences of the tension",
          "[continuation]") {
  const LargeKinematics law(3);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 n0 = Vec3(unit(random), unit(random), unit(random)).normalized();
    const double length = 0.5 + std::abs(unit(random)) * 1.5;
    const Vec3 du = 0.3 * length * Vec3(unit(random), unit(random), unit(random));
    const double kn = 1e10 * (1 + std::abs(unit(random)));
    const double ks = kn * std::abs(unit(random));
    const BondReference reference{n0, length};
    const Mat3 exact = jacobian_of(law, reference, du, kn, ks);
    const Mat3 numeric = central_difference_tangent(law, reference, du, kn, ks, 1e-5 * length);
    INFO("trial " << trial);
    CHECK((exact - numeric).norm() <= 1e-6 * exact.norm());
    // The assembly's block is the symmetric part.
    const Mat3 symmetric = tangent_of(law, reference, du, kn, ks);
    CHECK((symmetric - 0.5 * (exact + exact.transpose())).norm() <= 1e-15 * exact.norm());
    // tension() and deformation() describe the same law.
    const BondDeformation d = law.deformation(reference, du);
    const Vec3 n = (length * n0 + du).normalized();
    CHECK((tension_of(law, reference, du, kn, ks) - (kn * d.normal * n + ks * d.shear)).norm() <=
          1e-12 * kn * du.norm());
    CHECK(std::abs(d.shear.dot(n)) <= 1e-12 * du.norm());
  }
}

TEST_CASE("The large-kinematics Jacobian is symmetric only while the bond has not rotated",
          "[continuation]") {
  const LargeKinematics law(3);
  const Vec3 n0 = Vec3(1, 0, 1).normalized();
  const BondReference reference{n0, 1.0};
  const double kn = 3.0, ks = 1.0;
  const Mat3 stretched = jacobian_of(law, reference, 0.01 * n0, kn, ks);
  CHECK((stretched - stretched.transpose()).norm() <= 1e-14 * stretched.norm());
  // The skew part is -(kn - ks) n (P d0)' / r, antisymmetrized: for a rotation of about
  // 0.01 / sqrt(2) rad, |P d0| / r is about that angle.
  const Mat3 rotated = jacobian_of(law, reference, Vec3(0.0, 0.0, 0.01), kn, ks);
  const Mat3 skew = 0.5 * (rotated - rotated.transpose());
  const Vec3 d = n0 + Vec3(0.0, 0.0, 0.01);
  const Vec3 n = d.normalized();
  const Vec3 perpendicular_d0 = n0 - n.dot(n0) * n;
  const Mat3 expected = -(kn - ks) * (n * perpendicular_d0.transpose()) / d.norm();
  CHECK((skew - 0.5 * (expected - expected.transpose())).norm() <= 1e-14 * kn);
  CHECK(skew.norm() > 1e-3 * rotated.norm());
  // At du = 0 both laws have the same tangent.
  const Mat3 small = tangent_of(SmallKinematics(3), reference, Vec3::Zero(), kn, ks);
  CHECK((tangent_of(law, reference, Vec3::Zero(), kn, ks) - small).norm() <= 1e-14 * small.norm());
  CHECK((jacobian_of(law, reference, Vec3::Zero(), kn, ks) - small).norm() <= 1e-14 * small.norm());
}

TEST_CASE("A rigid rotation by theta strains a bond in both laws", "[continuation]") {
  // A bond of length L0 along x rotated by theta about y (x-z plane): x_j - x_i =
  // L0 (cos theta, 0, sin theta). By hand, |ds| = L0 |sin theta| in both laws, and
  // dn = L0 (cos theta - 1) with n0, dn = L0 (1 - cos theta) with the current n.
  const double length = 2.0, kn = 5.0, ks = 2.0;
  const Vec3 n0 = Vec3::UnitX();
  const BondReference reference{n0, length};
  for (const double theta : {1e-3, 0.1, pi / 6, pi / 2}) {
    const Vec3 rotated = length * Vec3(std::cos(theta), 0, std::sin(theta));
    const Vec3 du = rotated - length * n0;
    const BondDeformation large = LargeKinematics(3).deformation(reference, du);
    const BondDeformation small = SmallKinematics(3).deformation(reference, du);
    INFO("theta " << theta);
    // 1 - cos theta = 2 sin^2(theta / 2) without cancellation; du itself carries an
    // absolute rounding error of about 1e-16 L0.
    const double one_minus_cos = 2 * std::pow(std::sin(theta / 2), 2);
    const double margin = 1e-14 * length;
    CHECK(large.normal == Approx(length * one_minus_cos).epsilon(1e-12).margin(margin));
    CHECK(large.shear.norm() == Approx(length * std::sin(theta)).epsilon(1e-12).margin(margin));
    CHECK(small.normal == Approx(-length * one_minus_cos).epsilon(1e-12).margin(margin));
    CHECK(small.shear.norm() == Approx(length * std::sin(theta)).epsilon(1e-12).margin(margin));
    // ds = du - dn n = L0 (cos theta n - n0) = L0 sin theta (-sin theta, 0, cos theta): the
    // current bond's own normal direction.
    const Vec3 n = rotated / length;
    const Vec3 expected_shear =
        length * std::sin(theta) * Vec3(-std::sin(theta), 0, std::cos(theta));
    CHECK((large.shear - expected_shear).norm() <= 1e-12 * length);
    const Vec3 expected_tension = kn * length * one_minus_cos * n + ks * expected_shear;
    CHECK((tension_of(LargeKinematics(3), reference, du, kn, ks) - expected_tension).norm() <=
          1e-12 * kn * length);
  }
}

TEST_CASE("On an affine scene the CVODE path finds the closed-form first break", "[continuation]") {
  const Criterion criterion = GENERATE(Criterion::tensile, Criterion::elliptic);
  // The walls move by +-6 mm per unit 1e-3 of lambda, about 100 MPa of horizontal stress:
  // 40 MPa is reached near lambda 4e-4.
  const Scene scene = strength_scene(false, criterion, 40e6);
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  const FailureEvaluator evaluator(*scene.strength, model);
  const AffinePath affine = solver.affine_path();
  const double to = 1e-3;
  const FirstBreak expected = closed_form_first_break(model, affine, evaluator.parameters(), to);
  REQUIRE(expected.lambda > 0);
  REQUIRE(expected.lambda <= to);

  Vector u = affine.gravity;
  NonlinearPath path(model, solver, evaluator, scene.solver);
  const PathEvent event = path.advance(0.0, to, u);
  INFO("criterion " << to_string(criterion) << ", expected bond " << expected.tied.front()
                    << " (of " << expected.tied.size() << " tied) at " << expected.lambda
                    << ", found " << event.bond << " at " << event.lambda);
  CHECK(expected.contains(event.bond));
  CHECK(std::abs(event.lambda - expected.lambda) <= 1e-8 * expected.lambda);
  CHECK(max_abs(u - affine.at(event.lambda)) <=
        1e-8 * max_abs(affine.at(event.lambda)));
  // A linear law: one factorization for the whole path.
  CHECK(path.statistics().factorizations == 1);

  // From the event with the bond broken, the next advance starts again at f < 1 or reports
  // the cascade at once; either way it stays within [event, to].
  solver.set_pair_state(event.bond, PairState::open);
  solver.solve(event.lambda, u);
  const PathEvent next = path.advance(event.lambda, to, u);
  CHECK(next.lambda >= event.lambda);
  CHECK(next.lambda <= to);
}

TEST_CASE("A large-kinematics scene advances to its first break in equilibrium", "[continuation]") {
  const Scene scene = strength_scene(true, Criterion::tensile, 40e6);
  Model model = build_model(scene);
  REQUIRE_FALSE(model.is_linear());
  EquilibriumSolver solver(model, scene.solver);
  const FailureEvaluator evaluator(*scene.strength, model);
  Vector u = Vector::Zero(model.dofs().free_count);
  solver.solve(0.0, u);
  NonlinearPath path(model, solver, evaluator, scene.solver);
  const PathEvent event = path.advance(0.0, 1e-3, u);
  REQUIRE(event.bond >= 0);
  const double residual =
      max_abs(model.residual(u, event.lambda)) / solver.load_scale(event.lambda);
  CHECK(residual <= scene.solver.tolerance);
  const CriticalBond leader =
      evaluator.most_critical(model, model.full_displacement(u, event.lambda));
  CHECK(leader.bond == event.bond);
  CHECK(leader.index == Approx(1.0).epsilon(1e-8));

  // Rotations are of the order of the strain (1e-3 here): the event moves by about that
  // much relative to small kinematics.
  const Scene small_scene = strength_scene(false, Criterion::tensile, 40e6);
  Model small_model = build_model(small_scene);
  EquilibriumSolver small_solver(small_model, small_scene.solver);
  const FailureEvaluator small_evaluator(*small_scene.strength, small_model);
  const FirstBreak small = closed_form_first_break(small_model, small_solver.affine_path(),
                                                   small_evaluator.parameters(), 1e-3);
  CHECK(std::abs(event.lambda - small.lambda) <= 1e-2 * small.lambda);
}

TEST_CASE("Without events the large-kinematics path ends at the equilibrium KINSOL finds directly",
          "[continuation]") {
  const int dim = GENERATE(2, 3);
  Scene scene = dim == 2 ? testing::box_scene(2, 1.0, {12.0, 0, 6.0}, true)
                         : testing::box_scene(3, 1.0, {5.0, 3.0, 4.0}, true);
  scene.large_kinematics = true;
  scene.strength = testing::strength_of(Criterion::tensile, 1e15);  // never reached
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  const FailureEvaluator evaluator(*scene.strength, model);
  const double to = 0.05;  // rotations of a few per cent: the tangent is clearly nonsymmetric
  Vector u = Vector::Zero(model.dofs().free_count);
  solver.solve(0.0, u);
  NonlinearPath path(model, solver, evaluator, scene.solver);
  const PathEvent event = path.advance(0.0, to, u);
  CHECK(event.bond == -1);
  CHECK(event.lambda == to);
  const double load = solver.load_scale(to);
  CHECK(max_abs(model.residual(u, to)) <= scene.solver.tolerance * load);

  Vector direct = Vector::Zero(model.dofs().free_count);
  const EquilibriumReport report = solver.solve(to, direct);
  INFO("KINSOL from zero: " << report.newton_iterations
                            << " iterations; path: " << path.statistics().steps << " steps, "
                            << path.statistics().factorizations << " factorizations, "
                            << path.statistics().refinement_iterations << " refinement iterations");
  CHECK(max_abs(u - direct) <= 1e-7 * max_abs(direct));
  CHECK(path.statistics().refinement_iterations > 0);
}
