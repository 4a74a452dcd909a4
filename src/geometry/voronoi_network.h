// The Voronoi geometry of points in a box: Delaunay bonds with their facets, and the cells.
//
// Points within `band` of a face are mirrored across it (and across the pairs and triples
// of faces near edges and corners). An image is never nearer than its original to any
// point of the box, so inside the box the Voronoi diagram is that of the points alone;
// the images only close the cells of the points near the faces. Each facet is clipped to
// the box. A bond is a Delaunay edge between two points whose clipped facet has an area
// (2-D: a length) above `min_area`; the facet between a point and its own image is the
// piece of the face its cell owns. A cell's volume is the sum of the pyramids on its
// facets, A L / (2 D) each (L the distance to the neighbour, so L/2 the pyramid's height);
// the volumes add up to the box's.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "latfrac/base/linear_algebra.h"

namespace latfrac {

struct VoronoiNetwork {
  std::vector<std::array<std::int64_t, 2>> bonds;  // point indices i < j, sorted
  std::vector<double> facet_area;                  // per bond: m^2 (2-D: m)
  std::vector<Vec3> facet_centroid;                // per bond, m
  std::vector<double> cell_volume;                 // per point: m^3 (2-D: m^2)
  // Delaunay edges between two points whose facet has no area inside the box (flat
  // co-spherical sets, mostly where mirror images meet), left out.
  std::int64_t dropped_edges = 0;
  // Cells that own a piece of a face their point is not on (the wall guard makes it 0).
  std::int64_t cells_on_foreign_faces = 0;
};

// dim 2: the points' x and z in the box [0, extent]; dim 3: x, y, z. Throws Error when a
// kept point's cell is unbounded (a band too thin for the points' spacing).
VoronoiNetwork voronoi_network(int dim, const std::vector<Vec3>& points, const Vec3& extent,
                               double band, double min_area);

}  // namespace latfrac
