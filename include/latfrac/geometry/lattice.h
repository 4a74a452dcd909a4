// The lattice: nodes filling a box, the bonds between them, and which faces each node is on.
//
// Two kinds. The regular lattices: in 2-D a triangular lattice in the x-z plane (rows
// along x, row pitch sqrt(3)/2 a, every other row shifted by a/2), nearest neighbours
// only; in 3-D hexagonal close packing, triangular layers in x-y stacked ABAB along z at
// pitch sqrt(2/3) a, with the 12 nearest neighbours at a and, optionally, the 6
// next-nearest at sqrt(2) a.
//
// The box is filled from the origin with a whole number of lattice pitches along each
// axis, the number nearest to the requested size (3-D y: a whole number plus a half, so
// that both stacking sublattices reach both y faces); the lattice's own extent
// (`extent`) is what the loads use. A node within a/2 (inclusive) of a face of that
// extent belongs to the face: so the rows that end half a spacing short of a wall are
// held by it too. docs/model.md explains both choices.
//
// The random lattice (src/geometry/random_lattice.h): Poisson-disk points at a mean
// spacing a, seeded, with points on the box's corners, edges and faces; bonds along the
// edges of their Delaunay triangulation. Its extent is the requested size, and no node
// off a face lies within a/2 of it. Each node carries the volume of its Voronoi cell
// clipped to the box, each bond the area and centroid of the Voronoi facet its two nodes
// share: what the springs, gravity and node stresses of a random lattice use.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "latfrac/base/linear_algebra.h"

namespace latfrac {

enum class Face { x_min, x_max, y_min, y_max, z_min, z_max };
inline constexpr int face_count = 6;
const char* to_string(Face face);

// regular: triangular in 2-D, HCP in 3-D (a problem file names them "triangular" and
// "hcp"); random: Poisson-disk points with Delaunay bonds.
enum class LatticeKind : std::int8_t { regular = 0, random = 1 };
// "triangular", "hcp" or "random".
const char* lattice_kind_name(int dim, LatticeKind kind);

// What a problem file's [lattice] section asks for.
struct LatticeSpec {
  int dim = 2;                          // 2 (plane-strain x-z section) or 3
  double spacing = 0;                   // a, m: the bond length, or a random lattice's mean
  std::array<double, 3> size{0, 0, 0};  // box extent along x, y, z in m (y unused in 2-D)
  bool next_nearest = true;             // regular 3-D only: next-nearest bonds at sqrt(2) a
  LatticeKind kind = LatticeKind::regular;
  std::uint64_t seed = 0;  // random only: the point sampler's seed
  bool mirror = false;     // random only: the points reflected in x (x -> Lx - x)
};

// delaunay: a random lattice's bond (an edge of the Delaunay triangulation).
enum class BondKind : std::int8_t { nearest = 0, next_nearest = 1, delaunay = 2 };

struct Bond {
  std::int64_t i = 0, j = 0;  // i < j
  BondKind kind = BondKind::nearest;
};

// A random lattice's node on a face of the box owns a piece of that face: the part of its
// Voronoi cell's boundary that the face closes. What the face's support pushes on the node
// acts there (node_stress.h).
struct FacePiece {
  std::int64_t node = 0;
  int axis = 0;             // the face's normal axis: 0 x, 1 y, 2 z
  double area = 0;          // m^2 (2-D: m)
  Vec3 arm = Vec3::Zero();  // the piece's centroid minus the node's position, m
};

class Lattice {
 public:
  int dim = 2;
  LatticeKind kind = LatticeKind::regular;
  double spacing = 0;                   // a, m
  Vec3 extent = Vec3::Zero();           // lattice extent along x, y, z, m (y = 0 in 2-D)
  double node_volume = 0;               // V0: m^2 per metre (2-D) or m^3 (3-D); random: the mean
  double row_pitch = 0;                 // distance between rows (2-D) or layers (3-D), m; random: 0
  std::vector<Vec3> positions;          // reference positions X, m
  std::vector<std::uint8_t> face_mask;  // bit f set: node on Face f
  std::vector<Bond> bonds;
  std::vector<Vec3> bond_direction;  // unit vector n0 from i to j
  std::vector<double> bond_length;   // L0, m
  // Random lattices only; empty for regular ones, whose nodes all have node_volume.
  std::vector<double> node_volumes;       // V_i: the Voronoi cell in the box, m^3 (2-D: m^2)
  std::vector<double> bond_facet_area;    // A_b: the shared Voronoi facet, m^2 (2-D: m)
  std::vector<Vec3> bond_facet_centroid;  // c_b: the centroid of that facet, m
  std::vector<FacePiece> face_pieces;     // per node and face it is on, in node order

  bool is_random() const { return kind == LatticeKind::random; }
  // The volume node n stands for: V0, or its Voronoi cell's in a random lattice.
  double volume_of(std::int64_t node) const {
    return node_volumes.empty() ? node_volume : node_volumes[node];
  }
  std::int64_t node_count() const { return static_cast<std::int64_t>(positions.size()); }
  std::int64_t bond_count() const { return static_cast<std::int64_t>(bonds.size()); }
  bool on_face(std::int64_t node, Face face) const {
    return face_mask[node] & (1u << static_cast<int>(face));
  }
  // Whether a face piece is a piece of the top face (z = the lattice's height).
  bool on_top(const FacePiece& piece) const {
    return piece.axis == 2 && on_face(piece.node, Face::z_max);
  }
  // The axes that carry degrees of freedom: {x, z} in 2-D, {x, y, z} in 3-D.
  std::vector<int> axes() const {
    return dim == 2 ? std::vector<int>{0, 2} : std::vector<int>{0, 1, 2};
  }
};

// The most spacings along one axis that a lattice may have: beyond it the row counts
// overflow the integers that count them, and no memory would hold the nodes anyway.
inline constexpr double max_spacings_per_axis = 1e9;

// Builds the lattice of `spec`. Throws InputError for a non-positive spacing or size, a
// box smaller than two spacings along an axis, or a dimension other than 2 or 3.
// The same spec (a random lattice's seed included) gives the same lattice, bit for bit.
Lattice build_lattice(const LatticeSpec& spec);

// Each node's bonds, in increasing bond order: node n's are entries[start[n]] up to
// entries[start[n + 1]], each 2 b for a bond b whose end i it is and 2 b + 1 for its end j.
// A sum over a node's bonds in this order adds the same terms in the same order as a loop
// over all bonds that adds each bond to its two ends (the threaded sweeps' gathers).
struct NodeBonds {
  std::vector<std::int64_t> start, entries;
  std::int64_t node_count() const { return static_cast<std::int64_t>(start.size()) - 1; }
};
NodeBonds node_bonds(const Lattice& lattice);

}  // namespace latfrac
