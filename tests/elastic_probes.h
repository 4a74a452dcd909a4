// Test and benchmark helper: a lattice's macroscopic elasticity measured as a laboratory
// would, from the forces its faces need to hold a uniform strain.
//
// Two probes. Uniaxial strain between rollers: every face is a roller except the two
// normal to one axis, which move apart; the reactions on each face over its area are the
// stresses C_LLaa per unit strain. With every axis pulled in turn, the mean of the
// diagonal is lambda + 2 mu and the mean off the diagonal lambda (Lame constants), hence
// E and nu. Affine boundary: every face node follows u = eps X; the body's mean stress is
// (1/V) sum over the face nodes of sym(X (x) f), f the force that holds the node, which
// gives the tensor C column by column.
#pragma once

#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "latfrac/mechanics/calibration.h"
#include "latfrac/mechanics/model.h"
#include "latfrac/mechanics/node_stress.h"
#include "latfrac/solvers/equilibrium.h"

namespace latfrac::testing {

struct IsotropicModuli {
  double young = 0;    // Pa
  double poisson = 0;  // nu (in 2-D the 3-D constants of the plane-strain section)
};

inline IsotropicModuli from_lame(double lambda, double mu) {
  return {mu * (3 * lambda + 2 * mu) / (lambda + mu), lambda / (2 * (lambda + mu))};
}

// The model's full displacement at extension strain lambda under the given supports.
inline Vector solve_with(Model& model, const DofMap& dofs, double lambda,
                         const SolverOptions& options) {
  ModelEditor(model).set_dofs(dofs);
  EquilibriumSolver solver(model, options);
  return model.full_displacement(solver.affine_path().at(lambda), lambda);
}

inline double box_volume(const Lattice& lattice) {
  double volume = 1;
  for (int axis : lattice.axes()) volume *= lattice.extent[axis];
  return volume;
}

// Uniaxial strain between rollers along each axis in turn (the model has no gravity).
inline IsotropicModuli wall_moduli(Model& model, const SolverOptions& options = {}) {
  const Lattice& lattice = model.lattice;
  const std::vector<int> axes = lattice.axes();
  const int dim = lattice.dim;
  const double strain = 1e-3, volume = box_volume(lattice);
  double diagonal = 0, off_diagonal = 0;
  for (int load : axes) {
    std::array<FaceCondition, face_count> faces;
    faces.fill(FaceCondition::roller);
    faces[2 * load] = faces[2 * load + 1] = FaceCondition::extension;
    const Vector u = solve_with(model, build_dof_map(lattice, faces), strain, options);
    const Vector reactions = model.reactions(u);
    for (int c = 0; c < dim; ++c) {
      const int axis = axes[c];
      double force = 0;
      for (std::int64_t n = 0; n < lattice.node_count(); ++n)
        if (lattice.on_face(n, static_cast<Face>(2 * axis + 1))) force += reactions[n * dim + c];
      const double stress = force / (volume / lattice.extent[axis]) / strain;
      (axis == load ? diagonal : off_diagonal) += stress;
    }
  }
  diagonal /= dim;
  off_diagonal /= dim * (dim - 1);
  return from_lame(off_diagonal, (diagonal - off_diagonal) / 2);
}

// The state of an affine boundary u = strain X (X from the box's centre) on every face node.
struct AffineResponse {
  Vector displacement;
  Eigen::Matrix<double, 6, 1> mean_stress;      // Voigt xx yy zz yz xz xy, from the reactions
  Eigen::Matrix<double, 6, 1> interior_stress;  // the same over the cells 3 a inside
  std::vector<double> node_stress;              // node_stresses(), N x 6
};

// Is the node at least `margin` from every face?
inline bool inside_by(const Lattice& lattice, std::int64_t node, double margin) {
  for (int axis : lattice.axes()) {
    const double x = lattice.positions[node][axis];
    if (x < margin || x > lattice.extent[axis] - margin) return false;
  }
  return true;
}

inline AffineResponse affine_response(Model& model, const Mat3& strain,
                                      const SolverOptions& options = {}) {
  const Lattice& lattice = model.lattice;
  const std::vector<int> axes = lattice.axes();
  const int dim = lattice.dim;
  std::array<FaceCondition, face_count> faces;
  faces.fill(FaceCondition::fixed);
  DofMap dofs = build_dof_map(lattice, faces);
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3 affine = strain * (lattice.positions[n] - lattice.extent / 2);
    for (int c = 0; c < dim; ++c)
      if (dofs.free_index[n * dim + c] < 0) dofs.prescribed_rate[n * dim + c] = affine[axes[c]];
  }
  AffineResponse response;
  response.displacement = solve_with(model, dofs, 1.0, options);
  const Vector reactions = model.reactions(response.displacement);
  Mat3 sum = Mat3::Zero();
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    Vec3 force = Vec3::Zero();
    for (int c = 0; c < dim; ++c) force[axes[c]] = reactions[n * dim + c];
    sum += (lattice.positions[n] - lattice.extent / 2) * force.transpose();
  }
  const Mat3 mean = (sum + sum.transpose()) / (2 * box_volume(lattice));
  response.mean_stress << mean(0, 0), mean(1, 1), mean(2, 2), mean(1, 2), mean(0, 2), mean(0, 1);
  response.node_stress = node_stresses(model, response.displacement);
  // The mean stress of the cells at least 3 spacings inside, weighted by their volumes:
  // the body's stress there without the layer along the faces (whose bonds lie parallel
  // to the flat faces and make a box of a random lattice slightly cubic).
  response.interior_stress.setZero();
  double volume = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    if (!inside_by(lattice, n, 3 * lattice.spacing)) continue;
    const double v = lattice.volume_of(n);
    for (int k = 0; k < 6; ++k) response.interior_stress[k] += v * response.node_stress[6 * n + k];
    volume += v;
  }
  response.interior_stress /= volume;
  return response;
}

// Unit strain tensors of the Voigt components (engineering shear: eps_ij = eps_ji = 1/2).
inline Mat3 voigt_unit_strain(int k) {
  static const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  Mat3 e = Mat3::Zero();
  e(pairs[k][0], pairs[k][1]) += k < 3 ? 1.0 : 0.5;
  if (k >= 3) e(pairs[k][1], pairs[k][0]) += 0.5;
  return e;
}

// The Voigt components a lattice of this dimension has: xx, zz, xz in 2-D.
inline std::vector<int> voigt_components(int dim) {
  return dim == 2 ? std::vector{0, 2, 4} : std::vector{0, 1, 2, 3, 4, 5};
}

// The elastic tensor on the lattice's components (3 x 3 in 2-D: xx, zz, xz) under an
// affine boundary, Pa: from the reactions (the whole body), and from the mean stress of
// the cells 3 spacings inside.
struct AffineTensors {
  Eigen::MatrixXd whole, interior;
};

inline AffineTensors affine_tensors(Model& model, const SolverOptions& options = {}) {
  const std::vector<int> components = voigt_components(model.dim());
  const double strain = 1e-3;
  const int count = static_cast<int>(components.size());
  AffineTensors tensors{Eigen::MatrixXd(count, count), Eigen::MatrixXd(count, count)};
  for (int column = 0; column < count; ++column) {
    const AffineResponse r =
        affine_response(model, strain * voigt_unit_strain(components[column]), options);
    for (int row = 0; row < count; ++row) {
      tensors.whole(row, column) = r.mean_stress[components[row]] / strain;
      tensors.interior(row, column) = r.interior_stress[components[row]] / strain;
    }
  }
  return tensors;
}

inline Eigen::MatrixXd affine_tensor(Model& model, const SolverOptions& options = {}) {
  return affine_tensors(model, options).whole;
}

// Young's modulus along the direction at theta (radians) from x in the x-z plane: the
// stress over the strain along it under uniaxial stress, 1 / (m : S : m). In 2-D, from the
// plane-strain tensor: the plane-strain modulus E / (1 - nu^2) of an isotropic section.
inline double directional_young(const Eigen::MatrixXd& tensor, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(tensor.rows());
  if (tensor.rows() == 3) {
    m << c * c, s * s, c * s;
  } else {
    m << c * c, 0, s * s, 0, c * s, 0;
  }
  return 1 / m.dot(tensor.inverse() * m);
}

}  // namespace latfrac::testing
