// Builds triangular (2-D) and HCP (3-D) lattices in a box, or random ones, with bonds and
// face membership.
#include "latfrac/geometry/lattice.h"

#include <cmath>
#include <sstream>
#include <unordered_map>

#include "latfrac/base/error.h"
#include "random_lattice.h"

namespace latfrac {
namespace {

void validate(const LatticeSpec& spec) {
  if (spec.dim != 2 && spec.dim != 3) {
    throw InputError("lattice.dim: must be 2 or 3, got " + std::to_string(spec.dim));
  }
  if (!(spec.spacing > 0) || !std::isfinite(spec.spacing)) {
    throw InputError("lattice.spacing: must be a positive length in m");
  }
  const char* axis_names[] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    if (spec.dim == 2 && axis == 1) continue;
    const double length = spec.size[axis];
    if (!(length > 0) || !std::isfinite(length)) {
      throw InputError(std::string("lattice.size: the ") + axis_names[axis] +
                       " extent must be a positive length in m");
    }
    if (length < 2 * spec.spacing) {
      std::ostringstream message;
      message << "lattice.size: the " << axis_names[axis] << " extent " << length
              << " m is smaller than two spacings (2 x " << spec.spacing << " m)";
      throw InputError(message.str());
    }
    // (A lattice of no nodes was built at spacing 1e-15 under --force.)
    constexpr double most_spacings = max_spacings_per_axis;
    if (length / spec.spacing > most_spacings) {
      std::ostringstream message;
      message << "lattice.spacing: " << spec.spacing << " m puts " << length / spec.spacing
              << " spacings along the " << axis_names[axis] << " extent of " << length
              << " m, more than " << most_spacings
              << " (no machine holds such a lattice, even with --force); allowed: at most "
              << most_spacings << " spacings per axis";
      throw InputError(message.str());
    }
  }
}

// Lattice pitches along each axis and the whole number of them that fills the box.
struct Grid {
  double pitch_x = 0, pitch_y = 0, pitch_z = 0;
  long intervals_x = 0, intervals_y = 0, intervals_z = 0;
};

Grid grid_of(const LatticeSpec& spec) {
  const double a = spec.spacing;
  Grid grid;
  grid.pitch_x = a;
  grid.intervals_x = std::lround(spec.size[0] / a);
  if (spec.dim == 2) {
    grid.pitch_z = std::sqrt(3.0) / 2 * a;
  } else {
    grid.pitch_y = std::sqrt(3.0) / 2 * a;
    grid.pitch_z = std::sqrt(2.0 / 3.0) * a;
    // Half a row pitch beyond the last A row, so that the last rows of both stacking
    // sublattices (A at n p, B at n p + a / (2 sqrt 3)) lie within a/2 of the y_max face.
    grid.intervals_y = std::max(1L, std::lround(spec.size[1] / grid.pitch_y - 0.5));
  }
  grid.intervals_z = std::lround(spec.size[2] / grid.pitch_z);
  return grid;
}

// Reference positions, row by row (2-D) or layer by layer, row by row (3-D). A row holds
// the nodes whose shifted x lies inside [0, extent_x].
std::vector<Vec3> place_nodes(const LatticeSpec& spec, const Grid& grid, const Vec3& extent) {
  const double a = spec.spacing, tolerance = 1e-9 * a;
  std::vector<Vec3> positions;
  auto add_row = [&](double shift_x, double y, double z) {
    for (double x = shift_x; x <= extent.x() + tolerance; x += a) positions.emplace_back(x, y, z);
  };
  for (long k = 0; k <= grid.intervals_z; ++k) {
    const double z = k * grid.pitch_z;
    if (spec.dim == 2) {
      add_row((k % 2) * a / 2, 0, z);
      continue;
    }
    // HCP: B layers are shifted by (a/2, a / (2 sqrt 3)) against A layers.
    const bool layer_b = k % 2;
    const double layer_shift_x = layer_b ? a / 2 : 0,
                 layer_shift_y = layer_b ? a / (2 * std::sqrt(3.0)) : 0;
    for (long r = 0;; ++r) {
      const double y = layer_shift_y + r * grid.pitch_y;
      if (y > extent.y() + tolerance) break;
      const double shift = std::fmod(layer_shift_x + (r % 2) * a / 2, a);
      add_row(shift, y, z);
    }
  }
  return positions;
}

// Within a/2, inclusive: the shifted rows end exactly a/2 from the x walls, and a wall
// that skipped them would leave every other row unsupported.
std::uint8_t faces_of(const Vec3& position, const Vec3& extent, int dim, double spacing) {
  const double reach = spacing / 2 * (1 + 1e-9);
  std::uint8_t mask = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (dim == 2 && axis == 1) continue;
    if (position[axis] < reach) mask |= 1u << (2 * axis);
    if (extent[axis] - position[axis] < reach) mask |= 1u << (2 * axis + 1);
  }
  return mask;
}

// The pieces of the faces that close the cells of a random lattice's face nodes, from the
// bonds' facets alone. A closed cell has sum over its facets A (c - X) (x) n = V I and
// sum A n = 0 (n outward), so what the bonds' facets leave of these sums is the face
// pieces': the normal n_f of a piece gives its area A_f = -n_f . sum_b A_b n_b and its
// arm c_f - X = M n_f / A_f, with M = V I - sum_b A_b (c_b - X) (x) n_b (a corner node's
// pieces have orthogonal normals, so each is read off on its own).
std::vector<FacePiece> face_pieces_of(const Lattice& lattice) {
  const std::int64_t nodes = lattice.node_count();
  std::vector<Vec3> area_normal(nodes, Vec3::Zero());
  std::vector<Mat3> moment(nodes, Mat3::Zero());
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Bond& bond = lattice.bonds[b];
    const Vec3& n = lattice.bond_direction[b];  // outward from i, inward to j
    const double area = lattice.bond_facet_area[b];
    const Vec3& c = lattice.bond_facet_centroid[b];
    area_normal[bond.i] += area * n;
    area_normal[bond.j] -= area * n;
    moment[bond.i] += area * (c - lattice.positions[bond.i]) * n.transpose();
    moment[bond.j] -= area * (c - lattice.positions[bond.j]) * n.transpose();
  }
  Mat3 plane = Mat3::Identity();
  if (lattice.dim == 2) plane(1, 1) = 0;
  const double least = 1e-9 * std::pow(lattice.spacing, lattice.dim - 1);
  std::vector<FacePiece> pieces;
  for (std::int64_t node = 0; node < nodes; ++node) {
    for (int f = 0; f < face_count; ++f) {
      if (!lattice.on_face(node, static_cast<Face>(f))) continue;
      const int axis = f / 2;
      const Vec3 normal = (f % 2 == 0 ? -1.0 : 1.0) * Vec3::Unit(axis);
      const double area = -normal.dot(area_normal[node]);
      if (area <= least) continue;
      const Mat3 rest = lattice.node_volumes[node] * plane - moment[node];
      pieces.push_back({node, axis, area, rest * normal / area});
    }
  }
  return pieces;
}

// All pairs at distance a (and sqrt(2) a when wanted), found through a cell grid.
std::vector<Bond> find_bonds(const std::vector<Vec3>& positions, double a, bool next_nearest) {
  const double reach = next_nearest ? std::sqrt(2.0) * a : a;
  const double cell = reach * 1.01, tolerance = 1e-6 * a;
  auto key = [cell](const Vec3& p) {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x() / cell));
    const auto iy = static_cast<std::int64_t>(std::floor(p.y() / cell));
    const auto iz = static_cast<std::int64_t>(std::floor(p.z() / cell));
    return std::array<std::int64_t, 3>{ix, iy, iz};
  };
  auto hash = [](const std::array<std::int64_t, 3>& k) {
    return static_cast<std::size_t>(k[0] * 73856093 ^ k[1] * 19349663 ^ k[2] * 83492791);
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::int64_t>, decltype(hash)> cells(
      positions.size(), hash);
  for (std::int64_t n = 0; n < static_cast<std::int64_t>(positions.size()); ++n) {
    cells[key(positions[n])].push_back(n);
  }
  std::vector<Bond> bonds;
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(positions.size()); ++i) {
    const auto home = key(positions[i]);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find({home[0] + dx, home[1] + dy, home[2] + dz});
          if (found == cells.end()) continue;
          for (std::int64_t j : found->second) {
            if (j <= i) continue;
            const double distance = (positions[j] - positions[i]).norm();
            if (std::abs(distance - a) < tolerance) {
              bonds.push_back({i, j, BondKind::nearest});
            } else if (next_nearest && std::abs(distance - std::sqrt(2.0) * a) < tolerance) {
              bonds.push_back({i, j, BondKind::next_nearest});
            }
          }
        }
  }
  std::sort(bonds.begin(), bonds.end(),
            [](const Bond& p, const Bond& q) { return p.i != q.i ? p.i < q.i : p.j < q.j; });
  return bonds;
}

// The triangular or HCP lattice's nodes and bonds.
Lattice regular_lattice(const LatticeSpec& spec) {
  const Grid grid = grid_of(spec);
  Lattice lattice;
  lattice.dim = spec.dim;
  lattice.spacing = spec.spacing;
  const double extent_y = spec.dim == 3 ? (grid.intervals_y + 0.5) * grid.pitch_y : 0.0;
  lattice.extent = Vec3(grid.intervals_x * grid.pitch_x, extent_y, grid.intervals_z * grid.pitch_z);
  lattice.row_pitch = grid.pitch_z;
  const double a = spec.spacing;
  lattice.node_volume = spec.dim == 2 ? std::sqrt(3.0) / 2 * a * a : a * a * a / std::sqrt(2.0);
  lattice.positions = place_nodes(spec, grid, lattice.extent);
  lattice.bonds = find_bonds(lattice.positions, a, spec.dim == 3 && spec.next_nearest);
  return lattice;
}

}  // namespace

Lattice build_lattice(const LatticeSpec& spec) {
  validate(spec);
  Lattice lattice =
      spec.kind == LatticeKind::random ? build_random_lattice(spec) : regular_lattice(spec);
  lattice.face_mask.reserve(lattice.positions.size());
  for (const Vec3& p : lattice.positions) {
    lattice.face_mask.push_back(faces_of(p, lattice.extent, spec.dim, spec.spacing));
  }
  lattice.bond_direction.reserve(lattice.bonds.size());
  lattice.bond_length.reserve(lattice.bonds.size());
  for (const Bond& bond : lattice.bonds) {
    const Vec3 d0 = lattice.positions[bond.j] - lattice.positions[bond.i];
    lattice.bond_length.push_back(d0.norm());
    lattice.bond_direction.push_back(d0.normalized());
  }
  if (lattice.is_random()) lattice.face_pieces = face_pieces_of(lattice);
  return lattice;
}

const char* lattice_kind_name(int dim, LatticeKind kind) {
  if (kind == LatticeKind::random) return "random";
  return dim == 2 ? "triangular" : "hcp";
}

NodeBonds node_bonds(const Lattice& lattice) {
  NodeBonds index;
  index.start.assign(lattice.node_count() + 1, 0);
  for (const Bond& bond : lattice.bonds) {
    ++index.start[bond.i + 1];
    ++index.start[bond.j + 1];
  }
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) index.start[n + 1] += index.start[n];
  index.entries.resize(2 * lattice.bonds.size());
  std::vector<std::int64_t> next(index.start.begin(), index.start.end() - 1);
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    index.entries[next[lattice.bonds[b].i]++] = 2 * b;
    index.entries[next[lattice.bonds[b].j]++] = 2 * b + 1;
  }
  return index;
}

const char* to_string(Face face) {
  switch (face) {
    case Face::x_min:
      return "x_min";
    case Face::x_max:
      return "x_max";
    case Face::y_min:
      return "y_min";
    case Face::y_max:
      return "y_max";
    case Face::z_min:
      return "z_min";
    case Face::z_max:
      return "z_max";
  }
  return "unknown";
}

}  // namespace latfrac
