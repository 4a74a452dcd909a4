// The supports of a lattice from its face conditions.
#include "latfrac/mechanics/supports.h"

namespace latfrac {
namespace {

// Which condition wins where two faces meet on one component: the most restrictive.
int rank_of(FaceCondition condition) {
  switch (condition) {
    case FaceCondition::free:
      return 0;
    case FaceCondition::roller:
      return 1;
    case FaceCondition::extension:
      return 2;
    case FaceCondition::fixed:
      return 3;
  }
  return 0;
}

}  // namespace

const char* to_string(FaceCondition condition) {
  switch (condition) {
    case FaceCondition::free:
      return "free";
    case FaceCondition::roller:
      return "roller";
    case FaceCondition::fixed:
      return "fixed";
    case FaceCondition::extension:
      return "extension";
  }
  return "unknown";
}

DofMap build_dof_map(const Lattice& lattice, const std::array<FaceCondition, face_count>& faces,
                     std::optional<double> basal_discontinuity) {
  const std::vector<int> axes = lattice.axes();
  const int dim = lattice.dim;
  DofMap map;
  map.dim = dim;
  const std::int64_t dof_count = lattice.node_count() * dim;
  map.prescribed_base.assign(dof_count, 0.0);
  map.prescribed_rate.assign(dof_count, 0.0);
  std::vector<int> rank(dof_count, 0);
  const Vec3 centre = lattice.extent / 2;
  for (std::int64_t node = 0; node < lattice.node_count(); ++node) {
    for (int f = 0; f < face_count; ++f) {
      const Face face = static_cast<Face>(f);
      const int face_axis = f / 2;
      if (dim == 2 && face_axis == 1) continue;
      if (!lattice.on_face(node, face)) continue;
      const FaceCondition condition = faces[f];
      for (int c = 0; c < dim; ++c) {
        const bool normal = axes[c] == face_axis;
        const bool constrains =
            condition == FaceCondition::fixed || (normal && condition != FaceCondition::free);
        const std::int64_t dof = node * dim + c;
        if (!constrains || rank_of(condition) <= rank[dof]) continue;
        rank[dof] = rank_of(condition);
        map.prescribed_rate[dof] = condition == FaceCondition::extension
                                       ? lattice.positions[node][face_axis] - centre[face_axis]
                                       : 0.0;
      }
    }
  }
  if (basal_discontinuity) {
    const int x = 0;  // the x component is component 0 in 2-D and 3-D
    for (std::int64_t node = 0; node < lattice.node_count(); ++node) {
      if (!lattice.on_face(node, Face::z_min)) continue;
      const std::int64_t dof = node * dim + x;
      rank[dof] = rank_of(FaceCondition::fixed) + 1;
      map.prescribed_rate[dof] =
          lattice.positions[node].x() < *basal_discontinuity ? -centre.x() : centre.x();
    }
  }
  map.free_index.assign(dof_count, -1);
  for (std::int64_t dof = 0; dof < dof_count; ++dof) {
    if (rank[dof] == 0) map.free_index[dof] = map.free_count++;
  }
  return map;
}

}  // namespace latfrac
