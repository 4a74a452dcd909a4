// Bridson's Poisson-disk sampling of a box in stages (corners, edges, faces, interior),
// with the wall guard that keeps points off the faces' Voronoi cells (poisson_disk.h).
#include "poisson_disk.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "delaunay.h"
#include "seeded_random.h"

namespace latfrac {
namespace {

constexpr int attempts_per_point = 30;

// The sampler works in D local axes; in 2-D they are the global x and z.
template <int D>
using Point = Eigen::Matrix<double, D, 1>;

template <int D>
int global_axis(int local) {
  return D == 2 && local == 1 ? 2 : local;
}

// Steps `at` to the next cell of the block low..high (the first axis fastest); false
// after the last.
template <int D>
bool next_cell(int* at, const int* low, const int* high) {
  for (int a = 0; a < D; ++a) {
    if (++at[a] <= high[a]) return true;
    at[a] = low[a];
  }
  return false;
}

// Empty balls centred on the faces: a candidate inside one would own a piece of a face.
// Kept in a grid of cells 2r wide; each ball is listed in every cell its box overlaps.
template <int D>
class WallGuard {
 public:
  WallGuard(const Point<D>& size, double r) : cell_(2 * r) {
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) {
      cells_[a] = static_cast<int>(std::floor(size[a] / cell_)) + 1;
      total *= cells_[a];
    }
    grid_.assign(total, {});
  }

  void add(const Point<D>& centre, double radius_squared) {
    const double radius = std::sqrt(radius_squared);
    int low[D], high[D], at[D];
    for (int a = 0; a < D; ++a) {
      low[a] = cell_index(centre[a] - radius, a);
      high[a] = cell_index(centre[a] + radius, a);
      at[a] = low[a];
    }
    balls_.push_back({centre, radius_squared});
    const int ball = static_cast<int>(balls_.size()) - 1;
    do {
      grid_[flat_index(at)].push_back(ball);
    } while (next_cell<D>(at, low, high));
  }

  bool rejects(const Point<D>& p) const {
    int at[D];
    for (int a = 0; a < D; ++a) at[a] = cell_index(p[a], a);
    for (int ball : grid_[flat_index(at)]) {
      if ((p - balls_[ball].centre).squaredNorm() < balls_[ball].radius_squared) return true;
    }
    return false;
  }

 private:
  int cell_index(double x, int a) const {
    return std::clamp(static_cast<int>(std::floor(x / cell_)), 0, cells_[a] - 1);
  }
  std::size_t flat_index(const int* at) const {
    std::size_t index = 0;
    for (int a = D - 1; a >= 0; --a) index = index * cells_[a] + at[a];
    return index;
  }
  struct Ball {
    Point<D> centre;
    double radius_squared;
  };
  double cell_;
  int cells_[D];
  std::vector<Ball> balls_;
  std::vector<std::vector<int>> grid_;
};

// A flat of the box: per axis -1 (free), 0 (fixed at 0) or 1 (fixed at the box's size).
template <int D>
using Flat = std::array<int, D>;

template <int D>
class Sampler {
 public:
  Sampler(const Point<D>& size, double r)
      : size_(size), r_(r), r_squared_(r * r), cell_(r / std::sqrt(double(D))), guard_(size, r) {
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) {
      cells_[a] = static_cast<int>(std::floor(size[a] / cell_)) + 1;
      total *= cells_[a];
    }
    grid_.assign(total, -1);
  }

  // Bridson's algorithm on one flat, seeded with the points already on it (a corner: the
  // one point, if it fits).
  void fill(const Flat<D>& flat, SeededRandom& random) {
    int free_axes[D], free_count = 0;
    for (int a = 0; a < D; ++a)
      if (flat[a] < 0) free_axes[free_count++] = a;
    Point<D> p;
    for (int a = 0; a < D; ++a) p[a] = flat[a] == 1 ? size_[a] : 0.0;
    if (free_count == 0) {
      if (accepts(p)) insert(p);
      return;
    }
    std::vector<int> active;
    for (int k = 0; k < static_cast<int>(points_.size()); ++k)
      if (on_flat(points_[k], flat)) active.push_back(k);
    if (active.empty()) {
      for (int k = 0; k < free_count; ++k) p[free_axes[k]] = random.uniform() * size_[free_axes[k]];
      if (accepts(p)) {
        insert(p);
        active.push_back(static_cast<int>(points_.size()) - 1);
      }
    }
    while (!active.empty()) {
      const std::size_t slot = random.index(active.size());
      const Point<D> base = points_[active[slot]];
      bool placed = false;
      for (int attempt = 0; attempt < attempts_per_point && !placed; ++attempt) {
        double offset[D], norm_squared;
        do {  // uniform in the annulus r <= |offset| < 2r of the flat, by rejection
          norm_squared = 0;
          for (int k = 0; k < free_count; ++k) {
            offset[k] = (4 * random.uniform() - 2) * r_;
            norm_squared += offset[k] * offset[k];
          }
        } while (norm_squared < r_squared_ || norm_squared >= 4 * r_squared_);
        Point<D> candidate = base;
        bool inside = true;
        for (int k = 0; k < free_count; ++k) {
          const int a = free_axes[k];
          candidate[a] += offset[k];
          inside = inside && candidate[a] >= 0 && candidate[a] <= size_[a];
        }
        if (inside && accepts(candidate)) {
          insert(candidate);
          active.push_back(static_cast<int>(points_.size()) - 1);
          placed = true;
        }
      }
      if (!placed) {
        active[slot] = active.back();
        active.pop_back();
      }
    }
  }

  // The diametral balls of consecutive points on every edge of the box.
  void guard_edges() {
    for (int axis = 0; axis < D; ++axis) {
      for (int corner = 0; corner < (1 << D); ++corner) {
        if (corner & (1 << axis)) continue;
        Flat<D> edge;
        for (int a = 0; a < D; ++a) edge[a] = a == axis ? -1 : (corner >> a) & 1;
        std::vector<Point<D>> on;
        for (const Point<D>& p : points_)
          if (on_flat(p, edge)) on.push_back(p);
        std::sort(on.begin(), on.end(),
                  [axis](const Point<D>& p, const Point<D>& q) { return p[axis] < q[axis]; });
        for (std::size_t k = 0; k + 1 < on.size(); ++k) {
          guard_.add(0.5 * (on[k] + on[k + 1]), 0.25 * (on[k + 1] - on[k]).squaredNorm());
        }
      }
    }
    guarding_ = true;
  }

  // The circumballs of the 2-D Delaunay triangles of each face's points, those centred in
  // the face. The points within 4r of the face's edges are mirrored across them first, so
  // that the triangles near the edges are those of the face alone.
  void guard_faces() {
    const double band = 4 * r_;
    for (int axis = 0; axis < D; ++axis) {
      for (int side = 0; side < 2; ++side) {
        const int u = (axis + 1) % D, v = (axis + 2) % D;
        const double level = side ? size_[axis] : 0.0, width = size_[u], height = size_[v];
        std::vector<std::array<double, 2>> plane;
        for (const Point<D>& p : points_) {
          if (p[axis] != level) continue;
          const double x = p[u], y = p[v];
          const std::vector<double> xs = mirrors(x, width, band), ys = mirrors(y, height, band);
          for (double mx : xs)
            for (double my : ys) plane.push_back({mx, my});
        }
        const double tolerance = 1e-9 * r_;
        for (const auto& triangle : delaunay_triangles(plane)) {
          const auto& p0 = plane[triangle[0]];
          const auto& p1 = plane[triangle[1]];
          const auto& p2 = plane[triangle[2]];
          const double ax = p1[0] - p0[0], ay = p1[1] - p0[1];
          const double bx = p2[0] - p0[0], by = p2[1] - p0[1];
          const double twice_area = 2 * (ax * by - ay * bx);
          const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by;
          const double cx = (by * a2 - ay * b2) / twice_area, cy = (ax * b2 - bx * a2) / twice_area;
          const double x = p0[0] + cx, y = p0[1] + cy;
          if (x < -tolerance || x > width + tolerance || y < -tolerance || y > height + tolerance)
            continue;
          Point<D> centre;
          centre[axis] = level;
          centre[u] = x;
          centre[v] = y;
          guard_.add(centre, cx * cx + cy * cy);
        }
      }
    }
  }

  std::vector<Point<D>> take() { return std::move(points_); }

 private:
  // x and its images across 0 and `length` when it lies within `band` of them.
  static std::vector<double> mirrors(double x, double length, double band) {
    std::vector<double> images{x};
    if (x > 0 && x < band) images.push_back(-x);
    if (x < length && x > length - band) images.push_back(2 * length - x);
    return images;
  }
  bool on_flat(const Point<D>& p, const Flat<D>& flat) const {
    for (int a = 0; a < D; ++a)
      if (flat[a] >= 0 && p[a] != (flat[a] ? size_[a] : 0.0)) return false;
    return true;
  }
  int cell_of(const Point<D>& p, int a) const {
    return std::min(cells_[a] - 1, static_cast<int>(p[a] / cell_));
  }
  // At least r from every point placed so far, and outside the guard's balls.
  bool accepts(const Point<D>& p) const {
    if (guarding_ && guard_.rejects(p)) return false;
    int low[D], high[D], at[D];
    for (int a = 0; a < D; ++a) {
      const int k = cell_of(p, a);
      low[a] = std::max(0, k - 2);
      high[a] = std::min(cells_[a] - 1, k + 2);
      at[a] = low[a];
    }
    do {
      std::size_t index = 0;
      for (int a = D - 1; a >= 0; --a) index = index * cells_[a] + at[a];
      const int q = grid_[index];
      if (q >= 0 && (points_[q] - p).squaredNorm() < r_squared_) return false;
    } while (next_cell<D>(at, low, high));
    return true;
  }
  void insert(const Point<D>& p) {
    std::size_t index = 0;
    for (int a = D - 1; a >= 0; --a) index = index * cells_[a] + cell_of(p, a);
    grid_[index] = static_cast<int>(points_.size());
    points_.push_back(p);
  }

  Point<D> size_;
  double r_, r_squared_, cell_;
  int cells_[D];
  std::vector<int> grid_;  // per cell: the point in it, or -1
  std::vector<Point<D>> points_;
  WallGuard<D> guard_;
  bool guarding_ = false;
};

template <int D>
std::vector<Vec3> sample(const Vec3& extent, double min_distance, std::uint64_t seed) {
  Point<D> size;
  for (int a = 0; a < D; ++a) size[a] = extent[global_axis<D>(a)];
  Sampler<D> sampler(size, min_distance);
  SeededRandom random(seed);
  // Flats by their number of free axes: corners, edges, (3-D) faces, the interior.
  int flats = 1;
  for (int a = 0; a < D; ++a) flats *= 3;
  for (int free_count = 0; free_count <= D; ++free_count) {
    for (int code = 0; code < flats; ++code) {
      Flat<D> flat;
      int rest = code, count = 0;
      for (int a = 0; a < D; ++a) {
        flat[a] = rest % 3 - 1;
        rest /= 3;
        count += flat[a] < 0;
      }
      if (count == free_count) sampler.fill(flat, random);
    }
    if (free_count == 1) sampler.guard_edges();
    if constexpr (D == 3) {
      if (free_count == 2) sampler.guard_faces();
    }
  }
  std::vector<Vec3> points;
  for (const Point<D>& p : sampler.take()) {
    Vec3 q = Vec3::Zero();
    for (int a = 0; a < D; ++a) q[global_axis<D>(a)] = p[a];
    points.push_back(q);
  }
  return points;
}

}  // namespace

double poisson_disk_distance(int dim, double spacing) {
  // sqrt(0.6148 sqrt(3) / 2) and cbrt(0.5767 / sqrt(2)) as literals: a libm cbrt may
  // differ by an ulp between compilers (one folds it exactly, another calls glibc), and
  // that would change every point.
  return spacing * (dim == 2 ? 0x1.759892cf51025p-1 : 0x1.7bad75778401ep-1);
}

std::vector<Vec3> poisson_disk_points(int dim, const Vec3& extent, double min_distance,
                                      std::uint64_t seed) {
  return dim == 2 ? sample<2>(extent, min_distance, seed) : sample<3>(extent, min_distance, seed);
}

}  // namespace latfrac
