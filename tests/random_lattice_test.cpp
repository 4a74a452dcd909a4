// Random lattices: reproducible by seed, points r apart, exact faces, and Voronoi cells
// that tile the box and satisfy the divergence theorem.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "latfrac/base/error.h"
#include "latfrac/geometry/lattice.h"
#include "latfrac/scene/size_estimate.h"

using namespace latfrac;

namespace {

LatticeSpec random_spec(int dim, std::uint64_t seed) {
  LatticeSpec spec;
  spec.dim = dim;
  spec.kind = LatticeKind::random;
  spec.spacing = 1.0;
  spec.size = dim == 2 ? std::array{30.0, 0.0, 20.0} : std::array{8.0, 7.0, 6.0};
  spec.seed = seed;
  return spec;
}

bool same_lattice(const Lattice& p, const Lattice& q) {
  if (p.bond_count() != q.bond_count() || p.node_count() != q.node_count()) return false;
  for (std::int64_t b = 0; b < p.bond_count(); ++b) {
    if (p.bonds[b].i != q.bonds[b].i || p.bonds[b].j != q.bonds[b].j) return false;
  }
  return p.positions == q.positions && p.bond_facet_area == q.bond_facet_area &&
         p.bond_facet_centroid == q.bond_facet_centroid && p.node_volumes == q.node_volumes &&
         p.face_mask == q.face_mask;
}

double box_volume(const Lattice& lattice) {
  return lattice.extent.x() * lattice.extent.z() * (lattice.dim == 3 ? lattice.extent.y() : 1.0);
}

// The distance from a point to the nearest face of the box.
double face_distance(const Lattice& lattice, const Vec3& p) {
  double distance = std::numeric_limits<double>::infinity();
  for (int axis : lattice.axes())
    distance = std::min({distance, p[axis], lattice.extent[axis] - p[axis]});
  return distance;
}

}  // namespace

TEST_CASE("Random lattice: the same seed gives the same lattice bit for bit, another seed another",
          "[lattice][random]") {
  const int dim = GENERATE(2, 3);
  const Lattice first = build_lattice(random_spec(dim, 7));
  const Lattice again = build_lattice(random_spec(dim, 7));
  const Lattice other = build_lattice(random_spec(dim, 8));
  CHECK(same_lattice(first, again));
  CHECK_FALSE(same_lattice(first, other));
  CHECK(first.positions != other.positions);
}

TEST_CASE("Random lattice: points at least r apart, exactly on the faces or well inside",
          "[lattice][random]") {
  const int dim = GENERATE(2, 3);
  const Lattice lattice = build_lattice(random_spec(dim, 3));
  const double r = dim == 2 ? 0.7296796682426289 : 0.7415577610390789;
  double closest = std::numeric_limits<double>::infinity();
  for (std::int64_t i = 0; i < lattice.node_count(); ++i)
    for (std::int64_t j = i + 1; j < lattice.node_count(); ++j)
      closest = std::min(closest, (lattice.positions[i] - lattice.positions[j]).norm());
  CHECK(closest >= r);
  // A node on a face lies exactly in it; the wall guard keeps the others more than
  // r / sqrt(2) from every face, so the a/2 rule cannot mistake them.
  double inner = std::numeric_limits<double>::infinity();
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3& p = lattice.positions[n];
    for (int axis : lattice.axes()) {
      const auto low = static_cast<Face>(2 * axis), high = static_cast<Face>(2 * axis + 1);
      CHECK(lattice.on_face(n, low) == (p[axis] == 0.0));
      CHECK(lattice.on_face(n, high) == (p[axis] == lattice.extent[axis]));
    }
    if (lattice.face_mask[n] == 0) inner = std::min(inner, face_distance(lattice, p));
  }
  INFO("closest pair " << closest << " a, innermost off-face node " << inner << " a from a face");
  CHECK(inner >= r / std::sqrt(2.0));
  CHECK(lattice.row_pitch == 0);
  CHECK((lattice.extent - Vec3(lattice.extent.x(), 0, 0)).norm() > 0);
}

TEST_CASE("Random lattice: the Voronoi cells tile the box and obey the divergence theorem",
          "[lattice][random]") {
  // Over a closed cell, the facets' outward normals weighted by their areas sum to zero,
  // and sum A (c - x) (x) n = V I (Gauss's theorem for the fields 1 and x - x_i). With the
  // wall guard every cell of a node off the faces is closed by bond facets alone.
  const int dim = GENERATE(2, 3);
  const Lattice lattice = build_lattice(random_spec(dim, 5));
  double total = 0;
  for (double v : lattice.node_volumes) {
    CHECK(v > 0);
    total += v;
  }
  CHECK(total == Approx(box_volume(lattice)).epsilon(1e-12));
  CHECK(lattice.node_volume == Approx(box_volume(lattice) / lattice.node_count()));

  std::vector<Vec3> flux(lattice.node_count(), Vec3::Zero());
  std::vector<Mat3> moment(lattice.node_count(), Mat3::Zero());
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Bond& bond = lattice.bonds[b];
    CHECK(bond.kind == BondKind::delaunay);
    CHECK(lattice.bond_facet_area[b] > 0);
    const Vec3 n = lattice.bond_direction[b] * lattice.bond_facet_area[b];  // out of i
    const Vec3& c = lattice.bond_facet_centroid[b];
    flux[bond.i] += n;
    flux[bond.j] -= n;
    moment[bond.i] += (c - lattice.positions[bond.i]) * n.transpose();
    moment[bond.j] -= (c - lattice.positions[bond.j]) * n.transpose();
  }
  Mat3 identity = Mat3::Identity();
  if (dim == 2) identity(1, 1) = 0;
  double flux_error = 0, moment_error = 0;
  int closed = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    if (lattice.face_mask[n]) continue;
    ++closed;
    const double v = lattice.node_volumes[n];
    const double area = dim == 2 ? v : std::pow(v, 2.0 / 3.0);  // the cell's scale
    flux_error = std::max(flux_error, flux[n].norm() / area);
    moment_error = std::max(moment_error, (moment[n] / v - identity).cwiseAbs().maxCoeff());
  }
  INFO(closed << " closed cells: worst |sum A n| / scale " << flux_error
              << ", worst |sum A (c - x) n / V - I| " << moment_error);
  CHECK(closed > 100);
  CHECK(flux_error < 1e-10);
  CHECK(moment_error < 1e-10);
}

TEST_CASE("Random lattice: the face nodes' pieces tile each face of the box", "[lattice][random]") {
  // The pieces are read off what the bonds' facets leave of each face node's cell
  // (Lattice::face_pieces); the box's faces are known independently. Each face must be
  // covered once: the pieces' areas sum to the face's area, their area-weighted centroids
  // to the face's centre, and every centroid lies in the face's plane.
  const int dim = GENERATE(2, 3);
  const Lattice lattice = build_lattice(random_spec(dim, 5));
  for (int f = 0; f < face_count; ++f) {
    const int axis = f / 2;
    if (dim == 2 && axis == 1) continue;
    double area = 0, off_plane = 0;
    Vec3 moment = Vec3::Zero();
    const double plane = f % 2 == 0 ? 0.0 : lattice.extent[axis];
    for (const FacePiece& piece : lattice.face_pieces) {
      if (piece.axis != axis || !lattice.on_face(piece.node, static_cast<Face>(f))) continue;
      const Vec3 centroid = lattice.positions[piece.node] + piece.arm;
      off_plane = std::max(off_plane, std::abs(centroid[axis] - plane));
      area += piece.area;
      moment += piece.area * centroid;
    }
    double expected = 1;
    for (int other : lattice.axes())
      if (other != axis) expected *= lattice.extent[other];
    Vec3 centre = lattice.extent / 2;
    centre[axis] = plane;
    INFO(dim << "-D, face " << to_string(static_cast<Face>(f)) << ": pieces' area " << area
             << " of " << expected << ", largest distance off the plane " << off_plane);
    CHECK(area == Approx(expected).epsilon(1e-10));
    CHECK((moment / area - centre).norm() < 1e-9 * lattice.extent.maxCoeff());
    CHECK(off_plane < 1e-9 * lattice.extent.maxCoeff());
  }
}

TEST_CASE("Random lattice: the mean spacing gives the regular lattice's node density",
          "[lattice][random]") {
  // Nodes per volume away from the faces (whose own points add a skin), against the
  // triangular lattice's 2 / (sqrt(3) a^2) and the HCP lattice's sqrt(2) / a^3; and the
  // mean number of Delaunay neighbours (6 in 2-D, about 15 in 3-D).
  const int dim = GENERATE(2, 3);
  LatticeSpec spec = random_spec(dim, 11);
  spec.size = dim == 2 ? std::array{80.0, 0.0, 60.0} : std::array{16.0, 16.0, 16.0};
  const Lattice lattice = build_lattice(spec);
  const double margin = 3.0;
  double inner_volume = 1;
  for (int axis : lattice.axes()) inner_volume *= lattice.extent[axis] - 2 * margin;
  int inner = 0;
  for (const Vec3& p : lattice.positions) inner += face_distance(lattice, p) > margin;
  const double density = inner / inner_volume;
  const double regular = dim == 2 ? 2 / std::sqrt(3.0) : std::sqrt(2.0);
  std::vector<int> neighbours(lattice.node_count(), 0);
  for (const Bond& b : lattice.bonds) {
    ++neighbours[b.i];
    ++neighbours[b.j];
  }
  double mean = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n)
    if (face_distance(lattice, lattice.positions[n]) > margin) mean += neighbours[n];
  mean /= inner;
  INFO("density " << density << " against " << regular << "; mean neighbours " << mean);
  CHECK(density == Approx(regular).epsilon(0.02));
  if (dim == 2) {
    CHECK(mean == Approx(6.0).epsilon(0.02));  // Euler: a planar triangulation's interior
  } else {
    // Points of a Poisson process have 15.54 Delaunay neighbours on average; a minimum
    // distance makes the cells more regular and lowers it (measured: 15.0).
    CHECK(mean > 14.5);
    CHECK(mean < 15.54);
  }
  double shortest = 1e9, longest = 0;
  for (double length : lattice.bond_length) {
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
  }
  CHECK(shortest >= (dim == 2 ? 0.7296 : 0.7415));
  CHECK(longest < 2.1);
  // The size estimate that `latfrac check` prints (and `run` uses to refuse problems too
  // large for memory) is close to the lattice actually built, and never short of bonds.
  Scene scene;
  scene.lattice = spec;
  const SizeEstimate estimate = estimate_size(scene);
  INFO("estimated " << estimate.nodes << " nodes and " << estimate.bonds << " bonds; built "
                    << lattice.node_count() << " and " << lattice.bond_count());
  CHECK(std::abs(estimate.nodes - lattice.node_count()) < 0.1 * lattice.node_count());
  CHECK(estimate.bonds >= lattice.bond_count());
  CHECK(estimate.bonds < 1.25 * lattice.bond_count());  // small boxes: many face nodes
}

TEST_CASE("Random lattice: impossible boxes are rejected like regular ones", "[lattice][random]") {
  LatticeSpec spec = random_spec(2, 1);
  spec.size = {1.5, 0.0, 10.0};
  CHECK_THROWS_AS(build_lattice(spec), InputError);
  spec.size = {10.0, 0.0, 10.0};
  spec.spacing = -1;
  CHECK_THROWS_AS(build_lattice(spec), InputError);
}

TEST_CASE("Random lattice: lattice.mirror gives the mirror image of the seed's lattice, node for node",
          "[lattice][random]") {
  // Reflecting the points in x maps the Delaunay bonds, Voronoi facets and cells onto
  // themselves: the same bonds (by node pair), the same areas and volumes, the facet
  // centroids reflected, and the x faces swapped.
  const int dim = GENERATE(2, 3);
  LatticeSpec spec = random_spec(dim, 5);
  const Lattice plain = build_lattice(spec);
  spec.mirror = true;
  const Lattice mirrored = build_lattice(spec);
  REQUIRE(mirrored.node_count() == plain.node_count());
  const double lx = plain.extent.x();
  for (std::int64_t n = 0; n < plain.node_count(); ++n) {
    INFO("node " << n);
    CHECK(mirrored.positions[n].x() == lx - plain.positions[n].x());
    CHECK(mirrored.positions[n].y() == plain.positions[n].y());
    CHECK(mirrored.positions[n].z() == plain.positions[n].z());
    CHECK(mirrored.node_volumes[n] == Approx(plain.node_volumes[n]).epsilon(1e-9));
    CHECK(mirrored.on_face(n, Face::x_min) == plain.on_face(n, Face::x_max));
    CHECK(mirrored.on_face(n, Face::z_min) == plain.on_face(n, Face::z_min));
  }
  std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> by_pair;
  for (std::int64_t b = 0; b < plain.bond_count(); ++b) by_pair[{plain.bonds[b].i, plain.bonds[b].j}] = b;
  REQUIRE(mirrored.bond_count() == plain.bond_count());
  for (std::int64_t b = 0; b < mirrored.bond_count(); ++b) {
    const auto found = by_pair.find({mirrored.bonds[b].i, mirrored.bonds[b].j});
    REQUIRE(found != by_pair.end());
    const std::int64_t p = found->second;
    CHECK(mirrored.bond_facet_area[b] == Approx(plain.bond_facet_area[p]).epsilon(1e-9));
    const Vec3& c = mirrored.bond_facet_centroid[b];
    const Vec3& d = plain.bond_facet_centroid[p];
    CHECK(c.x() == Approx(lx - d.x()).margin(1e-9 * lx));
    CHECK(c.z() == Approx(d.z()).margin(1e-9 * lx));
  }
}
