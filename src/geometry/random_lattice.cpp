// Builds a random lattice from Poisson-disk points and their clipped Voronoi diagram.
#include "random_lattice.h"

#include <cmath>

#include "poisson_disk.h"
#include "voronoi_network.h"

namespace latfrac {

Lattice build_random_lattice(const LatticeSpec& spec) {
  Lattice lattice;
  lattice.dim = spec.dim;
  lattice.kind = LatticeKind::random;
  lattice.spacing = spec.spacing;
  lattice.extent = Vec3(spec.size[0], spec.dim == 3 ? spec.size[1] : 0.0, spec.size[2]);
  lattice.row_pitch = 0;  // the top face is the surface: its nodes' cells end there

  const double r = poisson_disk_distance(spec.dim, spec.spacing);
  lattice.positions = poisson_disk_points(spec.dim, lattice.extent, r, spec.seed);
  // The mirror image of the same points, node for node: a scene and its mirror image
  // (docs/validation.md checks that faults mirror with the scene).
  if (spec.mirror)
    for (Vec3& p : lattice.positions) p.x() = lattice.extent.x() - p.x();
  // The mirror band: 4 r holds every point whose cell could reach a face (an empty ball
  // of the sampler is at most about 2 r across).
  const double min_area = 1e-9 * (spec.dim == 2 ? spec.spacing : spec.spacing * spec.spacing);
  VoronoiNetwork network =
      voronoi_network(spec.dim, lattice.positions, lattice.extent, 4 * r, min_area);

  lattice.bonds.reserve(network.bonds.size());
  for (const auto& [i, j] : network.bonds) lattice.bonds.push_back({i, j, BondKind::delaunay});
  lattice.bond_facet_area = std::move(network.facet_area);
  lattice.bond_facet_centroid = std::move(network.facet_centroid);
  lattice.node_volumes = std::move(network.cell_volume);
  double volume = lattice.extent.x() * lattice.extent.z();
  if (spec.dim == 3) volume *= lattice.extent.y();
  lattice.node_volume = volume / static_cast<double>(lattice.positions.size());
  return lattice;
}

}  // namespace latfrac
