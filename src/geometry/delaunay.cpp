// CGAL's 2-D and 3-D Delaunay triangulations, read out as edges with their Voronoi facets.
//
// The kernel has exact predicates and inexact constructions (Epick): the topology is exact,
// the circumcentres are doubles. Range insertion sorts the points along a Hilbert curve
// after a shuffle by boost::rand48 with its fixed default seed, so the same points give
// the same triangulation, in the same order, every run.
#include "delaunay.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_with_circumcenter_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <utility>

namespace latfrac {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

using VertexBase2 = CGAL::Triangulation_vertex_base_with_info_2<std::int64_t, Kernel>;
using Structure2 =
    CGAL::Triangulation_data_structure_2<VertexBase2, CGAL::Triangulation_face_base_2<Kernel>>;
using Delaunay2 = CGAL::Delaunay_triangulation_2<Kernel, Structure2>;

// Cells keep their circumcentre, which every edge around them asks for.
using VertexBase3 = CGAL::Triangulation_vertex_base_with_info_3<std::int64_t, Kernel>;
using CellBase3 = CGAL::Delaunay_triangulation_cell_base_with_circumcenter_3<Kernel>;
using Structure3 = CGAL::Triangulation_data_structure_3<VertexBase3, CellBase3, CGAL::Sequential_tag>;
using Delaunay3 = CGAL::Delaunay_triangulation_3<Kernel, Structure3>;

// One edge's facet while the triangulation is read: its ends, and per circumcentre the
// sorted point indices of the triangle or tetrahedron it belongs to (a key that does not
// depend on memory).
struct Facet {
  std::array<std::int64_t, 2> edge;
  std::vector<std::pair<std::array<std::int64_t, 4>, Vec3>> ring;
};

template <class Cell>
std::array<std::int64_t, 4> key_of(const Cell& cell, int vertices) {
  std::array<std::int64_t, 4> key{-1, -1, -1, -1};
  for (int k = 0; k < vertices; ++k) key[k] = cell->vertex(k)->info();
  std::sort(key.begin(), key.begin() + vertices);
  return key;
}

// CGAL reports an edge from whichever of its cells has the lower address, and so starts
// its ring of cells there: the order of the edges and the first vertex of each facet
// change from run to run (and the sums over them in the last bit). Here they are put in
// an order of point indices alone: the edges sorted, each ring started at its smallest
// key and turned towards the smaller of that key's two neighbours.
VoronoiFacets canonical(std::vector<Facet> collected, std::int64_t unbounded) {
  for (Facet& facet : collected) {
    auto& ring = facet.ring;
    const auto smallest = std::min_element(
        ring.begin(), ring.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
    std::rotate(ring.begin(), smallest, ring.end());
    if (ring.size() > 2 && ring.back().first < ring[1].first) std::reverse(ring.begin() + 1, ring.end());
  }
  std::sort(collected.begin(), collected.end(),
            [](const Facet& p, const Facet& q) { return p.edge < q.edge; });
  VoronoiFacets facets;
  facets.unbounded = unbounded;
  facets.edges.reserve(collected.size());
  facets.begin.reserve(collected.size() + 1);
  for (const Facet& facet : collected) {
    facets.edges.push_back(facet.edge);
    facets.begin.push_back(static_cast<std::int64_t>(facets.vertices.size()));
    for (const auto& [key, vertex] : facet.ring) facets.vertices.push_back(vertex);
  }
  facets.begin.push_back(static_cast<std::int64_t>(facets.vertices.size()));
  return facets;
}

VoronoiFacets facets_2d(const std::vector<Vec3>& points, std::int64_t kept) {
  std::vector<std::pair<Kernel::Point_2, std::int64_t>> input;
  input.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    input.emplace_back(Kernel::Point_2(points[k].x(), points[k].z()), static_cast<std::int64_t>(k));
  const Delaunay2 triangulation(input.begin(), input.end());

  std::vector<Facet> collected;
  std::int64_t unbounded = 0;
  for (auto edge = triangulation.finite_edges_begin(); edge != triangulation.finite_edges_end();
       ++edge) {
    const auto face = edge->first;
    const int opposite = edge->second;
    const std::int64_t a = face->vertex(Delaunay2::cw(opposite))->info();
    const std::int64_t b = face->vertex(Delaunay2::ccw(opposite))->info();
    if (a >= kept && b >= kept) continue;
    const auto other = face->neighbor(opposite);
    if (triangulation.is_infinite(face) || triangulation.is_infinite(other)) {
      ++unbounded;
      continue;
    }
    Facet facet{{std::min(a, b), std::max(a, b)}, {}};
    for (const auto& f : {face, other}) {
      const Kernel::Point_2 centre = triangulation.circumcenter(f);
      facet.ring.emplace_back(key_of(f, 3), Vec3(centre.x(), 0.0, centre.y()));
    }
    collected.push_back(std::move(facet));
  }
  return canonical(std::move(collected), unbounded);
}

VoronoiFacets facets_3d(const std::vector<Vec3>& points, std::int64_t kept) {
  std::vector<std::pair<Kernel::Point_3, std::int64_t>> input;
  input.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec3& p = points[k];
    input.emplace_back(Kernel::Point_3(p.x(), p.y(), p.z()), static_cast<std::int64_t>(k));
  }
  const Delaunay3 triangulation(input.begin(), input.end());

  std::vector<Facet> collected;
  std::int64_t unbounded = 0;
  for (auto edge = triangulation.finite_edges_begin(); edge != triangulation.finite_edges_end();
       ++edge) {
    const auto cell = edge->first;
    const std::int64_t a = cell->vertex(edge->second)->info();
    const std::int64_t b = cell->vertex(edge->third)->info();
    if (a >= kept && b >= kept) continue;
    Facet facet{{std::min(a, b), std::max(a, b)}, {}};
    bool bounded = true;
    auto around = triangulation.incident_cells(*edge);
    const auto first = around;
    do {
      if (triangulation.is_infinite(around)) {
        bounded = false;
        break;
      }
      const Kernel::Point_3& centre = around->circumcenter();
      facet.ring.emplace_back(key_of(around, 4), Vec3(centre.x(), centre.y(), centre.z()));
    } while (++around != first);
    if (!bounded) {
      ++unbounded;
      continue;
    }
    collected.push_back(std::move(facet));
  }
  return canonical(std::move(collected), unbounded);
}

}  // namespace

VoronoiFacets voronoi_facets(int dim, const std::vector<Vec3>& points, std::int64_t kept) {
  return dim == 2 ? facets_2d(points, kept) : facets_3d(points, kept);
}

std::vector<std::array<std::int64_t, 3>> delaunay_triangles(
    const std::vector<std::array<double, 2>>& points) {
  std::vector<std::pair<Kernel::Point_2, std::int64_t>> input;
  input.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    input.emplace_back(Kernel::Point_2(points[k][0], points[k][1]), static_cast<std::int64_t>(k));
  const Delaunay2 triangulation(input.begin(), input.end());
  std::vector<std::array<std::int64_t, 3>> triangles;
  triangles.reserve(triangulation.number_of_faces());
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end();
       ++face) {
    triangles.push_back({face->vertex(0)->info(), face->vertex(1)->info(), face->vertex(2)->info()});
  }
  return triangles;
}

}  // namespace latfrac
