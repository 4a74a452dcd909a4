// Delaunay triangulations and their dual Voronoi facets, behind a plain interface.
//
// delaunay.cpp is the one file that includes CGAL (the Computational Geometry Algorithms
// Library, 5.5): CGAL is header-only, and a translation unit with its 3-D triangulation
// takes about 20 s and 1 GB of memory to compile. Everything else sees only these types.
// CGAL's exact predicates make the triangulation's topology exact, also for the
// co-circular and co-spherical points that mirror images create (docs/model.md says why
// CGAL and notes its licence).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "latfrac/base/linear_algebra.h"

namespace latfrac {

// The Delaunay edges with at least one end among the first `kept` points, and the Voronoi
// facet dual to each: the circumcentres of the triangles (2-D: two, the facet is the
// segment between them) or tetrahedra (3-D: in order around the edge, the facet is the
// polygon through them) that share the edge.
struct VoronoiFacets {
  std::vector<std::array<std::int64_t, 2>> edges;  // point indices, first < second
  std::vector<std::int64_t> begin;  // edge k's facet: vertices[begin[k] .. begin[k + 1])
  std::vector<Vec3> vertices;       // circumcentres, m (2-D: y = 0)
  // Edges with a kept end whose facet reaches infinity; they are left out. Non-zero means
  // the caller's mirror images did not surround the kept points.
  std::int64_t unbounded = 0;
};

// dim 2: the triangulation of the points' (x, z); dim 3: of (x, y, z). The result depends
// only on the points and their order, never on the run: bit for bit the same each time.
VoronoiFacets voronoi_facets(int dim, const std::vector<Vec3>& points, std::int64_t kept);

// The Delaunay triangles of points in a plane, as indices into `points`.
std::vector<std::array<std::int64_t, 3>> delaunay_triangles(
    const std::vector<std::array<double, 2>>& points);

}  // namespace latfrac
