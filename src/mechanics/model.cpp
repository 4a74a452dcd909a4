// The forces of a model: internal (spring) forces, residuals and reactions.
#include "latfrac/mechanics/model.h"

namespace latfrac {

Vector Model::full_displacement(const Vector& free_displacement, double lambda) const {
  Vector u(dofs.dof_count());
  for (std::int64_t dof = 0; dof < dofs.dof_count(); ++dof) {
    const std::int64_t f = dofs.free_index[dof];
    u[dof] = f >= 0 ? free_displacement[f]
                    : dofs.prescribed_base[dof] + lambda * dofs.prescribed_rate[dof];
  }
  return u;
}

Vec3 Model::node_displacement(const Vector& displacement, std::int64_t node) const {
  if (lattice.dim == 2) return {displacement[2 * node], 0.0, displacement[2 * node + 1]};
  return {displacement[3 * node], displacement[3 * node + 1], displacement[3 * node + 2]};
}

// Adds bond b's force to both its nodes: +t on j, -t on i (t its tension vector).
void Model::add_bond_force(const Vector& displacement, std::int64_t b, Vector& force) const {
  const bool in_contact = contact_capable(b) && contact_active[b];
  if (!intact[b] && !in_contact) return;
  const Bond& bond = lattice.bonds[b];
  const Vec3& n0 = lattice.bond_direction[b];
  const Vec3 du = bond_displacement(displacement, b);
  const Vec3 t = intact[b] ? law->tension({n0, lattice.bond_length[b]}, du, normal_stiffness[b],
                                          shear_stiffness[b])
                           : Vec3(normal_stiffness[b] * n0.dot(du) * n0);
  const int d = dim();
  for (int c = 0; c < d; ++c) {
    const double component = t[d == 2 ? 2 * c : c];
    force[bond.j * d + c] += component;
    force[bond.i * d + c] -= component;
  }
}

Vector Model::internal_force(const Vector& displacement) const {
  Vector force = Vector::Zero(dofs.dof_count());
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) add_bond_force(displacement, b, force);
  return force;
}

Vector Model::internal_force(const Vector& displacement,
                             const std::vector<std::int64_t>& bonds) const {
  Vector force = Vector::Zero(dofs.dof_count());
  for (std::int64_t b : bonds) add_bond_force(displacement, b, force);
  return force;
}

Vector Model::residual(const Vector& free_displacement, double lambda) const {
  const Vector unbalanced =
      internal_force(full_displacement(free_displacement, lambda)) - external_force;
  Vector r(dofs.free_count);
  for (std::int64_t dof = 0; dof < dofs.dof_count(); ++dof) {
    if (dofs.free_index[dof] >= 0) r[dofs.free_index[dof]] = unbalanced[dof];
  }
  return r;
}

Vector Model::reactions(const Vector& displacement) const {
  Vector r = internal_force(displacement) - external_force;
  for (std::int64_t dof = 0; dof < dofs.dof_count(); ++dof) {
    if (dofs.free_index[dof] >= 0) r[dof] = 0;
  }
  return r;
}

}  // namespace latfrac
