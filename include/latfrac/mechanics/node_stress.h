// Node stresses from the bond forces (the virial), tension positive.
//
//   sigma_i = (1 / (2 V0)) sum over the bonds b of node i of sym(d_b (x) t_b)
// with d_b the reference bond vector and t_b its tension vector. Under an affine strain
// an interior node's stress equals C : eps. In 2-D plane strain the out-of-plane stress
// is sigma_yy = nu (sigma_xx + sigma_zz). Nodes on a free surface have fewer bonds and
// show a correspondingly smaller virial.
#pragma once

#include <vector>

#include "latfrac/mechanics/model.h"

namespace latfrac {

// Voigt order per node: xx, yy, zz, yz, xz, xy (Pa), N x 6 row-major.
std::vector<double> node_stresses(const Model& model, const Vector& displacement);

}  // namespace latfrac
