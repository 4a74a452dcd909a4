// The tangent stiffness matrix on the free degrees of freedom, in CHOLMOD's layout.
//
// Compressed sparse columns with 64-bit indices, upper triangle only (CHOLMOD's
// stype = 1). The pattern holds every bond that exists in the lattice, broken or not, so
// it is built once and the symbolic factorization is reused for the whole run; a
// broken bond merely contributes zeros. Each bond remembers where its blocks live, so
// refilling the values is one pass over the bonds.
#pragma once

#include <cstdint>
#include <vector>

#include "latfrac/mechanics/model.h"

namespace latfrac {

class StiffnessMatrix {
 public:
  explicit StiffnessMatrix(const Model& model);

  // Refills the values with the tangents of the pairs' laws, in their states, at the full
  // displacement u (open pairs contribute nothing).
  void assemble(const Model& model, const Vector& displacement);

  std::int64_t size() const { return static_cast<std::int64_t>(column_start_.size()) - 1; }
  std::int64_t nonzeros() const { return static_cast<std::int64_t>(row_index_.size()); }

  std::vector<std::int64_t>& column_start() { return column_start_; }
  std::vector<std::int64_t>& row_index() { return row_index_; }
  std::vector<double>& values() { return values_; }

 private:
  std::vector<std::int64_t> column_start_, row_index_;
  std::vector<double> values_;
  // Value slot of the entry (row dof a of node i, column dof b of node j) of bond b's
  // off-diagonal block, a * dim + b, or -1 when either dof is prescribed.
  std::vector<std::int64_t> bond_slot_;
  // Value slot of the upper entry (a, b), a <= b, of node n's diagonal block.
  std::vector<std::int64_t> node_slot_;
  int dim_ = 2;
};

}  // namespace latfrac
