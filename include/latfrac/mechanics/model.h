// The mechanical model of a scene: lattice, bond springs, supports, loads and the bond law.
//
// The supports (which degrees of freedom are prescribed, and how) are in supports.h;
// scene/model_builder.h builds a Model from a problem file's scene.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "latfrac/base/linear_algebra.h"
#include "latfrac/geometry/lattice.h"
#include "latfrac/mechanics/bond_law.h"
#include "latfrac/mechanics/supports.h"

namespace latfrac {

class Model {
 public:
  Lattice lattice;
  std::vector<double> normal_stiffness;  // kn per bond
  std::vector<double> shear_stiffness;   // ks per bond
  std::vector<std::uint8_t> intact;      // per bond
  std::vector<std::uint8_t> precut;      // per bond: crosses a pre-cut (starts broken)
  // Per-bond moduli and strengths (layers and heterogeneity make them differ), Pa.
  std::vector<double> bond_young, bond_shear_modulus, bond_sigma0, bond_tau0;
  // Contact (when the scene names it): a broken nearest-neighbour or pre-cut bond keeps a
  // compression-only normal spring kn, frictionless. contact_active marks the active set:
  // forces and stiffness use exactly the active springs (a linear law), and the
  // continuation's active-set iteration keeps the set consistent with dn <= 0.
  bool contact = false;
  std::vector<std::uint8_t> contact_active;
  std::vector<double> node_poisson;  // per node, for the 2-D out-of-plane stress
  DofMap dofs;
  Vector external_force;  // per dof (gravity), N (2-D: N per metre)
  std::unique_ptr<BondLaw> law;

  int dim() const { return lattice.dim; }
  // The full displacement (every dof) from the free part at extension strain lambda.
  Vector full_displacement(const Vector& free_displacement, double lambda) const;
  // Internal (spring) force per dof: the gradient of the stored energy.
  Vector internal_force(const Vector& displacement) const;
  // The same, summed over the listed bonds only.
  Vector internal_force(const Vector& displacement, const std::vector<std::int64_t>& bonds) const;
  // Out-of-balance force on the free dofs: internal minus external. Zero at equilibrium.
  Vector residual(const Vector& free_displacement, double lambda) const;
  // Reaction forces on the prescribed dofs (internal minus external), zero on free dofs.
  Vector reactions(const Vector& displacement) const;
  // The displacement of node n as a 3-vector (y = 0 in 2-D).
  Vec3 node_displacement(const Vector& displacement, std::int64_t node) const;
  // Relative displacement u_j - u_i of bond b.
  Vec3 bond_displacement(const Vector& displacement, std::int64_t bond) const {
    return node_displacement(displacement, lattice.bonds[bond].j) -
           node_displacement(displacement, lattice.bonds[bond].i);
  }
  // Adds bond b's spring (or active contact) force to `force`.
  void add_bond_force(const Vector& displacement, std::int64_t bond, Vector& force) const;
  // May broken bond b carry a contact spring?
  bool contact_capable(std::int64_t bond) const {
    return contact && !intact[bond] &&
           (lattice.bonds[bond].kind == BondKind::nearest || precut[bond]);
  }
};

}  // namespace latfrac
