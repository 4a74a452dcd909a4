// Node stresses from the bond forces (the virial), tension positive.
//
// Regular lattices (the branch form):
//   sigma_i = (1 / (2 V0)) sum over the bonds b of node i of sym(d_b (x) t_b)
// with d_b the reference bond vector and t_b its tension vector. Under an affine strain
// an interior node's stress equals C : eps. Nodes on a free surface have fewer bonds and
// show a correspondingly smaller virial.
//
// Random lattices (the facet-centroid form, with the node's Voronoi cell volume V_i):
//   sigma_i = (1 / V_i) sum over the bonds b of node i of sym((c_b - X_i) (x) f_ib)
// with c_b the centroid of the bond's Voronoi facet and f_ib the bond's force on node i.
// Over a closed cell sum A_b (c_b - X_i) (x) n_b = V_i I, so a uniform stress gives every
// node exactly that stress; the branch form, with arms d_b / 2 that do not end on the
// cell's facets, adds a scatter of about 7 % (rms over mean) that is pure geometry. A node
// on a free surface has a cell that ends at the surface and reads the stress there. A node
// that a face holds has the support's force on its piece of the face (Lattice::face_pieces)
// in the sum as well, sym((c_f - X_i) (x) R_k e_k) per held component k, with R_k what
// balances its intact bonds and (with the loads) its weight: without it the cell is not
// closed and the node reads a shear the face does not carry (docs/model.md, section 6).
//
// In 2-D plane strain the out-of-plane stress is sigma_yy = nu (sigma_xx + sigma_zz).
#pragma once

#include <cstdint>
#include <vector>

#include "latfrac/mechanics/model.h"

namespace latfrac {

// Voigt order per node: xx, yy, zz, yz, xz, xy (Pa), N x 6 row-major.
std::vector<double> node_stresses(const Model& model, const Vector& displacement);
// node_stresses at the listed nodes only, the same numbers bit for bit; the other
// nodes' entries are NaN. For a few bonds' criterion: a sum over those nodes' bonds
// instead of a sweep over every bond.
std::vector<double> node_stresses_at(const Model& model, const Vector& displacement,
                                     const std::vector<std::int64_t>& nodes);
// The part linear in the displacement: the stresses' change along a path's direction
// (without the loads the supports' forces balance in node_stresses).
std::vector<double> node_stress_rates(const Model& model, const Vector& direction);

// Both along an affine path, in one sweep over the bonds: node_stresses(at_zero) and
// node_stress_rates(per_unit), the same numbers bit for bit.
struct NodeStressPath {
  std::vector<double> at_zero, per_unit;
};
NodeStressPath node_stress_path(const Model& model, const Vector& at_zero, const Vector& per_unit);
// node_stress_path at the listed nodes only, the same numbers bit for bit; the other
// nodes' entries are NaN.
NodeStressPath node_stress_path_at(const Model& model, const Vector& at_zero,
                                   const Vector& per_unit, const std::vector<std::int64_t>& nodes);

// Per node, a bound B on how far its stress can move with the displacement under the
// small-kinematics law: for any change du of the displacement, with the same intact
// bonds and supports, the change of the node's stress tensor (in 2-D its x-z part) has a
// Frobenius norm of at most B max|du|, every bond counted as intact. So the traction on
// any plane (in 2-D: any plane whose normal lies in the section), and its normal and
// shear parts, move by at most that much too.
std::vector<double> node_stress_bounds(const Model& model);

}  // namespace latfrac
