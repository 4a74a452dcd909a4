// KINSOL + CHOLMOD: one Newton iteration on an affine scene, the affine path, failures.
#include "latfrac/solvers/equilibrium.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "latfrac/base/error.h"
#include "scenes.h"

using namespace latfrac;

TEST_CASE("KINSOL converges in one Newton iteration on an affine scene", "[equilibrium]") {
  const int dim = GENERATE(2, 3);
  const Scene scene = testing::box_scene(dim, 1000.0, {20e3, 5e3, 10e3}, true);
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  Vector u = Vector::Zero(model.dofs().free_count);
  const double lambda = 0.01;
  const EquilibriumReport report = solver.solve(lambda, u);
  CHECK(report.newton_iterations == 1);
  CHECK(report.relative_residual < scene.solver.tolerance);
  // Independently: the residual of the returned state, relative to the load.
  const double load =
      max_abs(model.residual(Vector::Zero(model.dofs().free_count), lambda));
  CHECK(max_abs(model.residual(u, lambda)) / load < scene.solver.tolerance);
  CHECK(solver.counters().factorizations == 1);
}

TEST_CASE("The affine path from one two-column solve equals Newton at any lambda",
          "[equilibrium]") {
  const int dim = GENERATE(2, 3);
  const Scene scene = testing::box_scene(dim, 1000.0, {20e3, 5e3, 10e3}, true);
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  const AffinePath path = solver.affine_path();
  CHECK(solver.counters().factorizations == 1);
  for (double lambda : {0.0, 0.013, -0.02, 0.04}) {
    Vector u = Vector::Zero(model.dofs().free_count);
    solver.solve(lambda, u);
    const Vector from_path = path.at(lambda);
    CHECK(max_abs(u - from_path) / max_abs(from_path) < 1e-9);
  }
  // The factor of a linear scene is reused: still one factorization.
  CHECK(solver.counters().factorizations == 1);
}

TEST_CASE("A scene with a rigid-body motion fails with a message naming the call",
          "[equilibrium]") {
  Scene scene = testing::box_scene(2, 1.0, {10.0, 0, 6.0}, true);
  scene.faces.fill(FaceCondition::free);
  scene.faces[static_cast<int>(Face::z_min)] = FaceCondition::roller;  // x is unrestrained
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  Vector u = Vector::Zero(model.dofs().free_count);
  try {
    solver.solve(0.0, u);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK_THAT(e.what(),
               Catch::Contains("cholmod_l_factorize") && Catch::Contains("without resistance"));
  }
}

TEST_CASE("Residual checks see a NaN or an infinity wherever it sits", "[equilibrium]") {
  // A residual check that misses a NaN accepts a broken solve (tests/contact_cases_test.cpp).
  for (int size : {1, 2, 7, 64}) {
    for (int at = 0; at < size; ++at) {
      for (double bad : {std::nan(""), -std::numeric_limits<double>::infinity()}) {
        Vector v = Vector::LinSpaced(size, 1.0, 2.0);
        v[at] = bad;
        INFO("size " << size << ", bad entry at " << at);
        CHECK(max_abs(v) == std::numeric_limits<double>::infinity());
      }
    }
  }
  CHECK(max_abs(Vector()) == 0.0);
  CHECK(max_abs(Vector::LinSpaced(5, -3.0, 1.0)) == 3.0);
}
