// The forces of a model (internal forces, residuals, reactions) and the editor of its states.
#include "latfrac/mechanics/model.h"

namespace latfrac {

std::vector<std::uint8_t> Model::intact_flags() const {
  std::vector<std::uint8_t> flags(states_.size());
  for (std::size_t b = 0; b < states_.size(); ++b) flags[b] = states_[b] == PairState::intact;
  return flags;
}

Vector Model::full_displacement(const Vector& free_displacement, double lambda) const {
  Vector u(dofs_.dof_count());
  for (std::int64_t dof = 0; dof < dofs_.dof_count(); ++dof) {
    const std::int64_t f = dofs_.free_index[dof];
    u[dof] = f >= 0 ? free_displacement[f]
                    : dofs_.prescribed_base[dof] + lambda * dofs_.prescribed_rate[dof];
  }
  return u;
}

Vector Model::free_part(const Vector& full) const {
  Vector part(dofs_.free_count);
  for (std::int64_t dof = 0; dof < dofs_.dof_count(); ++dof) {
    if (dofs_.free_index[dof] >= 0) part[dofs_.free_index[dof]] = full[dof];
  }
  return part;
}

Vec3 Model::bond_tension(const Vector& displacement, std::int64_t b) const {
  const InteractionLaw* law = law_of(b);
  if (!law) return Vec3::Zero();
  return law->tension(springs(b), states_[b], bond_displacement(displacement, b));
}

// An open pair carries nothing (pair_state.h), so only the others are evaluated.
void Model::add_bond_force(const Vector& displacement, std::int64_t b, Vector& force) const {
  if (states_[b] == PairState::open) return;
  const InteractionLaw* law = law_of(b);
  if (!law) return;
  const Bond& bond = lattice.bonds[b];
  const Vec3 t = law->tension(springs(b), states_[b], bond_displacement(displacement, b));
  const int d = dim();
  for (int c = 0; c < d; ++c) {
    const double component = t[d == 2 ? 2 * c : c];
    force[bond.j * d + c] += component;
    force[bond.i * d + c] -= component;
  }
}

Vector Model::internal_force(const Vector& displacement) const {
  Vector force = Vector::Zero(dofs_.dof_count());
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) add_bond_force(displacement, b, force);
  return force;
}

Vector Model::internal_force(const Vector& displacement,
                             const std::vector<std::int64_t>& bonds) const {
  Vector force = Vector::Zero(dofs_.dof_count());
  for (std::int64_t b : bonds) add_bond_force(displacement, b, force);
  return force;
}

Vector Model::residual(const Vector& free_displacement, double lambda) const {
  return free_part(internal_force(full_displacement(free_displacement, lambda)) - external_force);
}

Vector Model::reactions(const Vector& displacement) const {
  Vector r = internal_force(displacement) - external_force;
  for (std::int64_t dof = 0; dof < dofs_.dof_count(); ++dof) {
    if (dofs_.free_index[dof] >= 0) r[dof] = 0;
  }
  return r;
}

void ModelEditor::set_laws(std::unique_ptr<BondLaw> bond_law,
                           std::unique_ptr<InteractionLaw> contact_law) {
  model_.bond_law_ = std::move(bond_law);
  model_.contact_law_ = std::move(contact_law);
  model_.memory_.clear();
  if (model_.has_friction()) model_.memory_.resize(model_.lattice.bond_count());
}

void ModelEditor::reset_states() {
  model_.states_.assign(model_.lattice.bond_count(), PairState::intact);
}

void ModelEditor::hold(const std::vector<std::int64_t>& nodes, const std::vector<int>& components,
                       const Vector& displacement) {
  DofMap& dofs = model_.dofs_;
  const int dim = model_.dim();
  for (std::int64_t node : nodes) {
    for (int c : components) {
      const std::int64_t dof = node * dim + c;
      if (dofs.free_index[dof] < 0) continue;
      dofs.free_index[dof] = -1;
      dofs.prescribed_base[dof] = displacement[dof];
      dofs.prescribed_rate[dof] = 0.0;
    }
  }
  dofs.free_count = 0;
  for (std::int64_t dof = 0; dof < dofs.dof_count(); ++dof) {
    if (dofs.free_index[dof] >= 0) dofs.free_index[dof] = dofs.free_count++;
  }
}

}  // namespace latfrac
