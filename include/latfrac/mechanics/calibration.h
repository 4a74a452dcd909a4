// Spring constants from (E, nu), and the elastic tensors used to verify them.
//
// The constants make the lattice, deformed affinely, carry exactly the isotropic
// continuum's elastic tensor (Cauchy-Born). With Lame constants lambda, mu of (E, nu):
//   2-D plane strain (per metre of thickness):
//     kn = (2/sqrt 3)(lambda + mu),  ks = (2/sqrt 3)(mu - lambda)
//   3-D HCP, nearest neighbours (next-nearest bonds get a quarter of each):
//     kn = (sqrt 2 / 5) E a / (1 - 2 nu),  ks = kn (1 - 4 nu) / (1 + nu)
// Both need ks >= 0, i.e. nu <= 1/4; docs/model.md derives them. Random lattices have
// their own calibration (random_calibration.h).
#pragma once

#include <Eigen/Core>

#include "latfrac/geometry/lattice.h"
#include "latfrac/mechanics/material.h"

namespace latfrac {

struct SpringConstants {
  double normal = 0;  // kn, N/m (3-D) or N/m per metre (2-D)
  double shear = 0;   // ks
};

// Throws InputError when nu is outside (-1, 1/4] or E is not positive.
void validate_material(const Material& material, const char* where = "material");
// The same for a lattice of the given kind: a random lattice takes 0 <= nu <= its largest
// (random_lattice_max_poisson).
void validate_material(const Material& material, int dim, LatticeKind kind,
                       const char* where = "material");

// The nearest-neighbour constants; next-nearest bonds take a quarter of each.
SpringConstants spring_constants(int dim, const Material& material, double spacing);
inline constexpr double next_nearest_fraction = 0.25;

// Elastic tensors in Voigt order (xx, yy, zz, yz, xz, xy), Pa. In 2-D only the x-z
// entries are meaningful (plane strain).
using VoigtTensor = Eigen::Matrix<double, 6, 6>;
VoigtTensor isotropic_tensor(const Material& material);
// The tensor of the lattice's unit cell under affine strain: the bond sum
// (1/V0) sum over one node's bonds of (1/2) k-weighted n n n n terms.
VoigtTensor lattice_tensor(int dim, const Material& material, double spacing, bool next_nearest);

}  // namespace latfrac
