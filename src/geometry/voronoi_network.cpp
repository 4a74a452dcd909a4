// Bonds, facets and cells of points in a box: mirror images, CGAL's facets, clipping.
#include "voronoi_network.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "delaunay.h"
#include "latfrac/base/error.h"

namespace latfrac {
namespace {

std::vector<int> axes_of(int dim) { return dim == 2 ? std::vector{0, 2} : std::vector{0, 1, 2}; }

// The points followed by their mirror images; image_of[k - points] is image k's original.
struct Mirrored {
  std::vector<Vec3> points;
  std::vector<std::int64_t> image_of;
};

Mirrored with_images(int dim, const std::vector<Vec3>& points, const Vec3& extent, double band) {
  Mirrored mirrored;
  mirrored.points = points;
  const std::vector<int> axes = axes_of(dim);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec3& p = points[k];
    // Per axis: the coordinates of p and of its images across the faces within the band.
    std::vector<std::vector<double>> choices;
    for (int axis : axes) {
      std::vector<double> values{p[axis]};
      if (p[axis] > 0 && p[axis] < band) values.push_back(-p[axis]);
      if (p[axis] < extent[axis] && p[axis] > extent[axis] - band)
        values.push_back(2 * extent[axis] - p[axis]);
      choices.push_back(values);
    }
    // Every combination but p itself.
    std::vector<std::size_t> pick(axes.size(), 0);
    while (true) {
      std::size_t a = 0;
      for (; a < axes.size(); ++a) {
        if (++pick[a] < choices[a].size()) break;
        pick[a] = 0;
      }
      if (a == axes.size()) break;
      Vec3 image = p;
      for (std::size_t b = 0; b < axes.size(); ++b) image[axes[b]] = choices[b][pick[b]];
      mirrored.points.push_back(image);
      mirrored.image_of.push_back(static_cast<std::int64_t>(k));
    }
  }
  return mirrored;
}

// Sutherland-Hodgman clipping to the box, with a tolerance that keeps a facet lying in a
// face. A 2-D facet is an open segment, a 3-D one a closed polygon.
std::vector<Vec3> clip_to_box(std::vector<Vec3> polygon, int dim, const Vec3& extent,
                              double tolerance) {
  const bool closed = dim == 3;
  for (int axis : axes_of(dim)) {
    for (int side = 0; side < 2 && !polygon.empty(); ++side) {
      const auto inside_by = [&](const Vec3& p) {
        return side == 0 ? p[axis] : extent[axis] - p[axis];
      };
      std::vector<Vec3> kept;
      const std::size_t count = polygon.size();
      for (std::size_t k = 0; k < count; ++k) {
        const Vec3& p = polygon[k];
        const bool p_inside = inside_by(p) >= -tolerance;
        if (p_inside) kept.push_back(p);
        if (!closed && k + 1 == count) break;
        const Vec3& q = polygon[(k + 1) % count];
        if (p_inside != (inside_by(q) >= -tolerance)) {
          const double t = inside_by(p) / (inside_by(p) - inside_by(q));
          Vec3 crossing = p + t * (q - p);
          crossing[axis] = side == 0 ? 0.0 : extent[axis];
          kept.push_back(crossing);
        }
      }
      polygon.swap(kept);
    }
  }
  return polygon;
}

struct Measure {
  double area = 0;  // m^2 (2-D: a length, m)
  Vec3 centroid = Vec3::Zero();
};

// A segment's length and midpoint (2-D), or a polygon's area and centroid by a fan of
// triangles, each signed by the facet's normal (3-D).
Measure measure(const std::vector<Vec3>& facet, int dim, const Vec3& normal) {
  Measure m;
  if (dim == 2) {
    if (facet.size() < 2) return m;
    m.area = (facet.back() - facet.front()).norm();
    m.centroid = 0.5 * (facet.front() + facet.back());
    return m;
  }
  if (facet.size() < 3) return m;
  double signed_area = 0;
  Vec3 moment = Vec3::Zero();
  for (std::size_t k = 1; k + 1 < facet.size(); ++k) {
    const double triangle =
        0.5 * normal.dot((facet[k] - facet[0]).cross(facet[k + 1] - facet[0]));
    signed_area += triangle;
    moment += triangle * (facet[0] + facet[k] + facet[k + 1]) / 3;
  }
  if (signed_area == 0) return m;
  m.area = std::abs(signed_area);
  m.centroid = moment / signed_area;
  return m;
}

}  // namespace

VoronoiNetwork voronoi_network(int dim, const std::vector<Vec3>& points, const Vec3& extent,
                               double band, double min_area) {
  const auto kept = static_cast<std::int64_t>(points.size());
  const Mirrored mirrored = with_images(dim, points, extent, band);
  const VoronoiFacets facets = voronoi_facets(dim, mirrored.points, kept);
  if (facets.unbounded > 0) {
    throw Error("random lattice: " + std::to_string(facets.unbounded) +
                " Voronoi facets of points in the box reach infinity; the mirror band (" +
                std::to_string(band) + " m) is too thin");
  }
  VoronoiNetwork network;
  network.cell_volume.assign(points.size(), 0.0);
  const double tolerance = 1e-12 * extent.maxCoeff();
  std::vector<std::array<std::int64_t, 2>> bonds;
  std::vector<double> areas;
  std::vector<Vec3> centroids;
  for (std::size_t e = 0; e < facets.edges.size(); ++e) {
    std::int64_t a = facets.edges[e][0], b = facets.edges[e][1];  // a < b, so a is kept
    const bool own_image = b >= kept && mirrored.image_of[b - kept] == a;
    if (b >= kept && !own_image) continue;  // meets the box only on its faces
    const Vec3 offset = mirrored.points[b] - points[a];
    const double length = offset.norm();
    const std::vector<Vec3> facet(facets.vertices.begin() + facets.begin[e],
                                  facets.vertices.begin() + facets.begin[e + 1]);
    const Measure m = measure(clip_to_box(facet, dim, extent, tolerance), dim, offset / length);
    const double pyramid = m.area * length / (2.0 * dim);
    if (own_image) {
      // A point on a face has no image across it: this piece of face belongs to a point
      // off the face.
      network.cell_volume[a] += pyramid;
      if (m.area > min_area) ++network.cells_on_foreign_faces;
      continue;
    }
    if (m.area <= min_area) {
      ++network.dropped_edges;
      continue;
    }
    network.cell_volume[a] += pyramid;
    network.cell_volume[b] += pyramid;
    bonds.push_back({a, b});
    areas.push_back(m.area);
    centroids.push_back(m.centroid);
  }
  std::vector<std::size_t> order(bonds.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t p, std::size_t q) { return bonds[p] < bonds[q]; });
  for (std::size_t k : order) {
    network.bonds.push_back(bonds[k]);
    network.facet_area.push_back(areas[k]);
    network.facet_centroid.push_back(centroids[k]);
  }
  return network;
}

}  // namespace latfrac
