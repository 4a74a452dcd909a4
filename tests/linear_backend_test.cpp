// The petsc backend (linear_backend.h, docs/parallel.md) against the cholmod backend, on
// one rank: after bonds break, its conjugate gradients preconditioned with the unbroken
// stiffness's factor must give what a fresh factorization of the broken stiffness gives,
// within the iteration count that the rank of the change bounds; and a mechanism must be
// named at the same unknown. Only in a build with PETSc.
#include "latfrac/solvers/linear_backend.h"

#include <catch2/catch.hpp>

#include "latfrac/base/error.h"
#include "latfrac/solvers/equilibrium.h"
#include "scenes.h"

using namespace latfrac;

namespace {

// The intact bonds of a node.
std::vector<std::int64_t> bonds_of(const Model& model, std::int64_t node) {
  std::vector<std::int64_t> found;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    const Bond& bond = model.lattice.bonds[b];
    if (bond.i == node || bond.j == node) found.push_back(b);
  }
  return found;
}

// The node nearest a point.
std::int64_t node_near(const Model& model, const Vec3& point) {
  std::int64_t best = 0;
  for (std::int64_t n = 0; n < static_cast<std::int64_t>(model.lattice.positions.size()); ++n)
    if ((model.lattice.positions[n] - point).norm() < (model.lattice.positions[best] - point).norm())
      best = n;
  return best;
}

}  // namespace

TEST_CASE("The petsc backend after breaks solves like a fresh factorization of the broken "
          "stiffness",
          "[backend]") {
  const int dim = GENERATE(2, 3);
  Scene scene = testing::box_scene(dim, 1000.0, {12e3, 4e3, 8e3}, true);
  Model reference_model = build_model(scene);
  Model petsc_model = build_model(scene);
  EquilibriumSolver reference(reference_model, scene.solver);
  scene.solver.backend = LinearBackendKind::petsc;
  EquilibriumSolver petsc(petsc_model, scene.solver);
  const double lambda = 0.002;
  // Both factorize the intact stiffness: the same answer to rounding.
  const AffinePath intact_ref = reference.checked_affine_path(lambda);
  const AffinePath intact_petsc = petsc.checked_affine_path(lambda);
  CHECK(max_abs(intact_petsc.at(lambda) - intact_ref.at(lambda)) <=
        1e-10 * max_abs(intact_ref.at(lambda)));

  // A cut of r bonds around a point inside the body, bond by bond.
  const std::int64_t centre = node_near(petsc_model, {6e3, 2e3, 4e3});
  const std::vector<std::int64_t> cut = bonds_of(petsc_model, centre);
  const std::int64_t r = static_cast<std::int64_t>(cut.size()) - 1;  // keep one: no mechanism
  for (std::int64_t k = 0; k < r; ++k) {
    reference.set_pair_state(cut[k], PairState::open);
    petsc.set_pair_state(cut[k], PairState::open);
  }
  // The truth: a fresh CHOLMOD factorization of the broken stiffness.
  reference.discard_factor();
  const AffinePath fresh = reference.checked_affine_path(lambda);
  const LinearBackend::Statistics before = petsc.factor().statistics();
  const AffinePath iterated = petsc.checked_affine_path(lambda);
  const LinearBackend::Statistics& after = petsc.factor().statistics();
  for (const auto& [a, b] : {std::pair{iterated.gravity, fresh.gravity},
                             std::pair{iterated.extension, fresh.extension}})
    CHECK(max_abs(a - b) <= 1e-9 * max_abs(b));
  // Solved by CG with the intact factor, not refactorized ...
  CHECK(after.factorizations == before.factorizations);
  const long solves = after.iterative_solves - before.iterative_solves;
  REQUIRE(solves >= 2);  // the path's two columns
  // ... within the bound: each broken bond changes the stiffness by rank dim (its normal
  // and shear springs), so CG converges in at most dim r + 1 iterations per solve in exact
  // arithmetic; a few more are allowed for rounding.
  const long iterations = after.iterations - before.iterations;
  CHECK(iterations <= solves * (dim * r + 1 + 2));
}

TEST_CASE("The petsc backend names a mechanism at the cholmod backend's unknown", "[backend]") {
  const int dim = GENERATE(2, 3);
  Scene scene = testing::box_scene(dim, 1000.0, {12e3, 4e3, 8e3}, true);
  std::array<long long, 2> unknowns{-2, -2};
  for (int which = 0; which < 2; ++which) {
    Model model = build_model(scene);
    if (which == 1) scene.solver.backend = LinearBackendKind::petsc;
    EquilibriumSolver solver(model, scene.solver);
    solver.checked_affine_path(0.001);  // a factor, which the breaks then change
    // Every bond of one node: the node floats free, a zero-energy motion.
    for (std::int64_t b : bonds_of(model, node_near(model, {6e3, 2e3, 4e3})))
      solver.set_pair_state(b, PairState::open);
    try {
      solver.checked_affine_path(0.001);
      FAIL("no mechanism reported");
    } catch (const SingularStiffness& singular) {
      unknowns[which] = singular.unknown();
    }
  }
  CHECK(unknowns[0] >= 0);
  CHECK(unknowns[1] == unknowns[0]);
}
