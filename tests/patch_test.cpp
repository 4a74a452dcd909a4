// Patch test: a block whose boundary layer moves affinely has an affine interior in
// equilibrium, and the interior's virial stress is C : eps.
#include <catch2/catch.hpp>

#include "latfrac/mechanics/calibration.h"
#include "latfrac/solvers/equilibrium.h"
#include "latfrac/mechanics/node_stress.h"
#include "scenes.h"

using namespace latfrac;

namespace {

// Prescribes u = eps X on every node whose neighbourhood is incomplete; the rest are free.
void prescribe_boundary_layer(Model& model, const Mat3& strain) {
  const Lattice& lattice = model.lattice;
  std::vector<int> bonds_per_node(lattice.node_count(), 0);
  for (const Bond& b : lattice.bonds) {
    ++bonds_per_node[b.i];
    ++bonds_per_node[b.j];
  }
  const int full = lattice.dim == 2 ? 6 : 18;
  const std::vector<int> axes = lattice.axes();
  const int dim = lattice.dim;
  DofMap dofs = model.dofs();
  dofs.free_count = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3 affine = strain * lattice.positions[n];
    for (int c = 0; c < dim; ++c) {
      const std::int64_t dof = n * dim + c;
      const bool boundary = bonds_per_node[n] < full;
      dofs.free_index[dof] = boundary ? -1 : dofs.free_count++;
      dofs.prescribed_base[dof] = boundary ? affine[axes[c]] : 0.0;
      dofs.prescribed_rate[dof] = 0.0;
    }
  }
  ModelEditor(model).set_dofs(dofs);
}

Vector voigt_strain(const Mat3& e) {
  Vector v(6);
  v << e(0, 0), e(1, 1), e(2, 2), 2 * e(1, 2), 2 * e(0, 2), 2 * e(0, 1);
  return v;
}

}  // namespace

TEST_CASE("Patch test: affine boundary gives an affine interior with stress C : eps",
          "[lattice][equilibrium]") {
  const int dim = GENERATE(2, 3);
  Mat3 strain;
  if (dim == 2) {
    strain << 1.0e-4, 0, 0.7e-4, 0, 0, 0, 0.7e-4, 0, -2.3e-4;
  } else {
    strain << 1.0e-4, 0.4e-4, 0.7e-4, 0.4e-4, -1.5e-4, -0.6e-4, 0.7e-4, -0.6e-4, 2.2e-4;
  }
  Scene scene = testing::box_scene(dim, 1.0, {10.0, 8.0, 9.0}, false);
  scene.faces.fill(FaceCondition::free);
  Model model = build_model(scene);
  prescribe_boundary_layer(model, strain);
  REQUIRE(model.dofs().free_count > 0);

  EquilibriumSolver solver(model, scene.solver);
  Vector free_u = Vector::Zero(model.dofs().free_count);
  solver.solve(0.0, free_u);
  const Vector u = model.full_displacement(free_u, 0.0);
  const std::vector<double> stress = node_stresses(model, u);

  const Vector expected_stress = isotropic_tensor(scene.material) * voigt_strain(strain);
  const double stress_scale = expected_stress.cwiseAbs().maxCoeff();
  double displacement_error = 0, displacement_scale = 0, stress_error = 0;
  int interior = 0;
  for (std::int64_t n = 0; n < model.lattice.node_count(); ++n) {
    if (model.dofs().free_index[n * dim] < 0) continue;
    ++interior;
    const Vec3 affine = strain * model.lattice.positions[n];
    displacement_error =
        std::max(displacement_error, (model.node_displacement(u, n) - affine).norm());
    displacement_scale = std::max(displacement_scale, affine.norm());
    for (int k = 0; k < 6; ++k) {
      stress_error = std::max(stress_error, std::abs(stress[n * 6 + k] - expected_stress[k]));
    }
  }
  INFO("dim " << dim << ", interior nodes " << interior);
  CHECK(interior > 10);
  CHECK(displacement_error / displacement_scale < 1e-9);
  CHECK(stress_error / stress_scale < 1e-6);
}
