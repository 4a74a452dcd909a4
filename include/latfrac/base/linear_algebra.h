// The vector and matrix types every layer shares, and a NaN-safe largest magnitude.
#pragma once

#include <Eigen/Core>

namespace latfrac {

using Vector = Eigen::VectorXd;  // displacements and forces, one entry per degree of freedom
using Vec3 = Eigen::Vector3d;    // a node's or bond's vector (x, y, z); y = 0 in 2-D
using Mat3 = Eigen::Matrix3d;

// The largest magnitude in v (0 when empty), and infinity when any entry is NaN or
// infinite: Eigen's maxCoeff may skip a NaN, which would let a broken solve pass a check.
double max_abs(const Vector& v);

}  // namespace latfrac
