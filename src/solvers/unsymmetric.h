// The LU of a nonsymmetric stiffness (slipping contacts), private to the solvers layer.
#pragma once

#include <Eigen/SparseCore>
#include <Eigen/UmfPackSupport>

#include "latfrac/solvers/equilibrium.h"

namespace latfrac {

struct EquilibriumSolver::Unsymmetric {
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  Matrix matrix;
  Eigen::UmfPackLU<Matrix> lu;
};

}  // namespace latfrac
