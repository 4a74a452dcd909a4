// Builds the stiffness pattern once and refills its values from the bond law.
#include "latfrac/mechanics/stiffness.h"

#include <algorithm>

namespace latfrac {

// Column c = free dof (j, b) holds, in increasing row order: the free dofs of every
// lower-numbered neighbour i of j (neighbours sorted), then the free dofs (j, a), a <= b.
// Free dofs are numbered in node order, so this order is sorted.
StiffnessMatrix::StiffnessMatrix(const Model& model) : dim_(model.dim()) {
  const Lattice& lattice = model.lattice;
  const DofMap& dofs = model.dofs();
  const int d = dim_;
  std::vector<std::vector<std::pair<std::int64_t, std::int64_t>>> lower(lattice.node_count());
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    lower[lattice.bonds[b].j].push_back({lattice.bonds[b].i, b});
  }
  bond_slot_.assign(lattice.bond_count() * d * d, -1);
  node_slot_.assign(lattice.node_count() * d * d, -1);
  column_start_.assign(1, 0);
  column_start_.reserve(dofs.free_count + 1);
  for (std::int64_t j = 0; j < lattice.node_count(); ++j) {
    auto& neighbours = lower[j];
    std::sort(neighbours.begin(), neighbours.end());
    for (int bj = 0; bj < d; ++bj) {
      if (dofs.free_index[j * d + bj] < 0) continue;
      for (const auto& [i, bond] : neighbours) {
        for (int ai = 0; ai < d; ++ai) {
          const std::int64_t row = dofs.free_index[i * d + ai];
          if (row < 0) continue;
          bond_slot_[bond * d * d + ai * d + bj] = static_cast<std::int64_t>(row_index_.size());
          row_index_.push_back(row);
        }
      }
      for (int aj = 0; aj <= bj; ++aj) {
        const std::int64_t row = dofs.free_index[j * d + aj];
        if (row < 0) continue;
        node_slot_[j * d * d + aj * d + bj] = static_cast<std::int64_t>(row_index_.size());
        row_index_.push_back(row);
      }
      column_start_.push_back(static_cast<std::int64_t>(row_index_.size()));
    }
  }
  values_.assign(row_index_.size(), 0.0);
}

void StiffnessMatrix::assemble(const Model& model, const Vector& displacement) {
  std::fill(values_.begin(), values_.end(), 0.0);
  const Lattice& lattice = model.lattice;
  const int d = dim_;
  const std::vector<int> axes = lattice.axes();
  auto add_to_node = [&](std::int64_t node, const Mat3& block) {
    for (int b = 0; b < d; ++b)
      for (int a = 0; a <= b; ++a) {
        const std::int64_t slot = node_slot_[node * d * d + a * d + b];
        if (slot >= 0) values_[slot] += block(axes[a], axes[b]);
      }
  };
  for (std::int64_t bond = 0; bond < lattice.bond_count(); ++bond) {
    const PairState state = model.state(bond);
    const InteractionLaw* law = model.law_of(bond);
    if (state == PairState::open || !law) continue;
    const Bond& pair = lattice.bonds[bond];
    const Vec3 du = model.bond_displacement(displacement, bond);
    const Mat3 tangent = law->tangent(model.springs(bond), state, du);
    add_to_node(pair.i, tangent);
    add_to_node(pair.j, tangent);
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) {
        const std::int64_t slot = bond_slot_[bond * d * d + a * d + b];
        if (slot >= 0) values_[slot] -= tangent(axes[a], axes[b]);
      }
  }
}

}  // namespace latfrac
