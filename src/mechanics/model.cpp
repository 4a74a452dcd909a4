// The forces of a model (internal forces, residuals, reactions) and the editor of its states.
#include "latfrac/mechanics/model.h"

#include "latfrac/base/error.h"
#include "latfrac/base/threads.h"

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

const NodeBonds& Model::node_bonds() const {
  if (node_bonds_.node_count() != lattice.node_count() ||
      static_cast<std::int64_t>(node_bonds_.entries.size()) != 2 * lattice.bond_count())
    node_bonds_ = latfrac::node_bonds(lattice);
  return node_bonds_;
}

namespace {

// Adds a bond's tension t to the force on one of its ends: +t on end j, -t on end i (in
// 2-D the x and z components).
void add_at_end(Vector& force, int d, std::int64_t node, const Vec3& t, bool end_j) {
  for (int c = 0; c < d; ++c) {
    const double component = t[d == 2 ? 2 * c : c];
    if (end_j) {
      force[node * d + c] += component;
    } else {
      force[node * d + c] -= component;
    }
  }
}

}  // namespace

// An open pair carries nothing (pair_state.h), and a bond without a law nothing either.
bool Model::carries_force(std::int64_t b) const {
  return states_[b] != PairState::open && law_of(b) != nullptr;
}

void Model::add_bond_force(const Vector& displacement, std::int64_t b, Vector& force) const {
  if (!carries_force(b)) return;
  const Bond& bond = lattice.bonds[b];
  const Vec3 t = bond_tension(displacement, b);
  add_at_end(force, dim(), bond.j, t, true);
  add_at_end(force, dim(), bond.i, t, false);
}

// On one thread, add_bond_force over all bonds. On more, in two passes: every bond's
// tension (each bond on its own), then each node's sum over its bonds in bond order
// (node_bonds()), the same terms in the same order: the same numbers on any number of
// threads.
Vector Model::internal_force(const Vector& displacement) const {
  const std::int64_t bonds = lattice.bond_count();
  if (threads::used(lattice.node_count(), threads::node_grain) == 1) {
    Vector force = Vector::Zero(dofs_.dof_count());
    for (std::int64_t b = 0; b < bonds; ++b) add_bond_force(displacement, b, force);
    return force;
  }
  std::vector<Vec3> tension(bonds);
  std::vector<std::uint8_t> carries(bonds, 0);
  threads::for_blocks(bonds, threads::bond_grain, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t b = first; b < last; ++b) {
      if (!carries_force(b)) continue;
      tension[b] = bond_tension(displacement, b);
      carries[b] = 1;
    }
  });
  const int d = dim();
  Vector force = Vector::Zero(dofs_.dof_count());
  const NodeBonds& index = node_bonds();
  threads::for_blocks(lattice.node_count(), threads::node_grain, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t n = first; n < last; ++n) {
      for (std::int64_t k = index.start[n]; k < index.start[n + 1]; ++k) {
        const std::int64_t b = index.entries[k] / 2;
        if (!carries[b]) continue;
        add_at_end(force, d, n, tension[b], index.entries[k] % 2 == 1);
      }
    }
  });
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

void ModelEditor::set_contact_normal(std::int64_t bond, const Vec3& normal) {
  if (!model_.contacts_along_cracks() || !model_.intact(bond))
    throw Error(
        "a contact's normal is set on a scene with contacts along cracks, before its "
        "bond breaks");
  model_.contact_normal[bond] = normal;
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
