// Finds the bonds that cross pre-cut faults: a side test against the cut's plane, a
// point-in-parallelogram test, and a bounding-box prefilter (a cut is small).
#include "latfrac/geometry/precut.h"

#include <Eigen/Geometry>
#include <optional>

namespace latfrac {
namespace {

// A cut as the parallelogram corner + s edge1 + t edge2, s, t in [0, 1]. A 2-D segment
// is extruded across y = 0, where every 2-D node lies, so one test serves both.
struct Cut {
  Vec3 corner, edge1, edge2;
  Vec3 normal;                                // unit normal of the cut's plane
  double g11 = 0, g12 = 0, g22 = 0, det = 0;  // Gram matrix of the edges, its determinant
  double slack1 = 0, slack2 = 0;              // eps as a fraction of each edge
  Vec3 box_min, box_max;                      // bounding box, widened by eps
};

Vec3 to_vec(const std::array<double, 3>& p) { return Vec3(p[0], p[1], p[2]); }

// The cut of `precut`, or nothing when it is degenerate (zero length or area): such a cut
// has no sides, so no bond can lie on both of them.
std::optional<Cut> make_cut(const Precut& precut, int dim, double spacing, double eps) {
  Cut cut;
  if (dim == 2) {
    const Vec3 from(precut.from[0], 0, precut.from[2]), to(precut.to[0], 0, precut.to[2]);
    cut.corner = from - Vec3(0, spacing, 0);
    cut.edge1 = to - from;
    cut.edge2 = Vec3(0, 2 * spacing, 0);
  } else {
    cut.corner = to_vec(precut.corner);
    cut.edge1 = to_vec(precut.edge1);
    cut.edge2 = to_vec(precut.edge2);
  }
  const double length1 = cut.edge1.norm(), length2 = cut.edge2.norm();
  const Vec3 cross = cut.edge1.cross(cut.edge2);
  if (length1 <= eps || length2 <= eps || cross.norm() <= 1e-9 * length1 * length2) {
    return std::nullopt;
  }
  cut.normal = cross.normalized();
  cut.g11 = cut.edge1.squaredNorm();
  cut.g12 = cut.edge1.dot(cut.edge2);
  cut.g22 = cut.edge2.squaredNorm();
  cut.det = cut.g11 * cut.g22 - cut.g12 * cut.g12;
  cut.slack1 = eps / length1;
  cut.slack2 = eps / length2;
  cut.box_min = cut.box_max = cut.corner;
  for (const Vec3& vertex : {Vec3(cut.corner + cut.edge1), Vec3(cut.corner + cut.edge2),
                             Vec3(cut.corner + cut.edge1 + cut.edge2)}) {
    cut.box_min = cut.box_min.cwiseMin(vertex);
    cut.box_max = cut.box_max.cwiseMax(vertex);
  }
  cut.box_min.array() -= eps;
  cut.box_max.array() += eps;
  return cut;
}

// The rule of precut.h: ends strictly on opposite sides, meeting point within the cut.
bool crosses(const Cut& cut, const Vec3& start, const Vec3& end, double eps) {
  const double side_start = cut.normal.dot(start - cut.corner);
  const double side_end = cut.normal.dot(end - cut.corner);
  const bool opposite =
      (side_start > eps && side_end < -eps) || (side_start < -eps && side_end > eps);
  if (!opposite) return false;
  const Vec3 meeting = start + side_start / (side_start - side_end) * (end - start);
  const Vec3 offset = meeting - cut.corner;
  const double along1 = cut.edge1.dot(offset), along2 = cut.edge2.dot(offset);
  const double s = (cut.g22 * along1 - cut.g12 * along2) / cut.det;
  const double t = (cut.g11 * along2 - cut.g12 * along1) / cut.det;
  return s >= -cut.slack1 && s <= 1 + cut.slack1 && t >= -cut.slack2 && t <= 1 + cut.slack2;
}

bool boxes_overlap(const Vec3& min1, const Vec3& max1, const Vec3& min2, const Vec3& max2) {
  return (min1.array() <= max2.array()).all() && (min2.array() <= max1.array()).all();
}

}  // namespace

std::vector<std::int64_t> bonds_crossing_precuts(const Lattice& lattice,
                                                 const std::vector<Precut>& precuts) {
  const double eps = 1e-9 * lattice.spacing;
  std::vector<Cut> cuts;
  for (const Precut& precut : precuts) {
    if (auto cut = make_cut(precut, lattice.dim, lattice.spacing, eps)) cuts.push_back(*cut);
  }
  std::vector<std::int64_t> severed;
  if (cuts.empty()) return severed;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Vec3& start = lattice.positions[lattice.bonds[b].i];
    const Vec3& end = lattice.positions[lattice.bonds[b].j];
    const Vec3 bond_min = start.cwiseMin(end), bond_max = start.cwiseMax(end);
    for (const Cut& cut : cuts) {
      if (!boxes_overlap(bond_min, bond_max, cut.box_min, cut.box_max)) continue;
      if (crosses(cut, start, end, eps)) {
        severed.push_back(b);  // bonds are visited in order: sorted and unique
        break;
      }
    }
  }
  return severed;
}

Vec3 precut_normal(const Precut& precut, int dim) {
  const std::optional<Cut> cut = make_cut(precut, dim, 1.0, 0.0);
  return cut ? cut->normal : Vec3::Zero();
}

}  // namespace latfrac
