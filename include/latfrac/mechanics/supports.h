// Supports: which degrees of freedom the faces of the box prescribe, and how they move.
//
// Degrees of freedom are numbered node * dim + c, where c runs over lattice.axes(). A
// degree of freedom is either free or prescribed; a prescribed one follows
// u = base + lambda * rate (walls move with the extension strain lambda). Free ones are
// numbered 0 .. free_count - 1 in the same order, which keeps the stiffness matrix's
// node blocks contiguous.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "latfrac/geometry/lattice.h"

namespace latfrac {

// What a face of the box imposes on the nodes that belong to it.
//   free:      nothing
//   roller:    the displacement normal to the face is zero
//   fixed:     the whole displacement is zero
//   extension: the displacement along the face's axis is lambda * (X - centre), i.e.
//              -lambda L/2 and +lambda L/2 on the x walls; tangential components free
enum class FaceCondition { free, roller, fixed, extension };
const char* to_string(FaceCondition condition);

struct DofMap {
  int dim = 2;
  std::vector<std::int64_t> free_index;  // per dof: index among free dofs, or -1 if prescribed
  std::vector<double> prescribed_base;   // per dof, m (zero for free dofs)
  std::vector<double> prescribed_rate;   // per dof, m per unit lambda
  std::int64_t free_count = 0;

  std::int64_t dof_count() const { return static_cast<std::int64_t>(free_index.size()); }
};

// Builds the supports of a lattice from per-face conditions. Where two faces meet on one
// component, the most restrictive condition wins. With `basal_discontinuity` = x_d (m),
// the x displacement of every base node (z_min face) is prescribed as well, overriding the
// base's own condition on x: nodes with X < x_d move with the left wall
// (-lambda L/2), the others with the right wall (+lambda L/2).
DofMap build_dof_map(const Lattice& lattice, const std::array<FaceCondition, face_count>& faces,
                     std::optional<double> basal_discontinuity = std::nullopt);

}  // namespace latfrac
