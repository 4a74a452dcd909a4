// Fault analysis: clusters of broken bonds, their fitted lines or planes, and grabens.
#include "latfrac/fault_analysis.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "latfrac/error.h"

namespace latfrac {

namespace {

constexpr double kDegree = M_PI / 180.0;
// A dip within this of 0 or 90 deg has no dip direction.
constexpr double kLevelToleranceDeg = 1.0;
// Faults that may bound a graben: inclined, neither near vertical nor near horizontal.
constexpr double kGrabenMinDipDeg = 20.0;
constexpr double kGrabenMaxDipDeg = 80.0;

using Point = Eigen::Vector3d;

void check_input(const RunResult& result, std::size_t index, const FaultOptions& options) {
  if (result.snapshots.empty()) throw InputError("the result has no snapshots: nothing to analyse");
  if (index >= result.snapshots.size()) {
    throw InputError("snapshot " + std::to_string(index) + " is out of range: the result has " +
                     std::to_string(result.snapshots.size()) + " snapshots (0 .. " +
                     std::to_string(result.snapshots.size() - 1) + ")");
  }
  if (result.scene.dim != 2 && result.scene.dim != 3) {
    throw InputError("the result's scene dimension is " + std::to_string(result.scene.dim) +
                     "; fault analysis needs 2 or 3");
  }
  if (!(result.scene.spacing > 0)) throw InputError("the result's lattice spacing is not positive");
  if (!(options.link_distance_spacings > 0)) {
    throw InputError("fault analysis: the link distance must be positive (spacings)");
  }
  if (options.min_bonds < 1) throw InputError("fault analysis: min_bonds must be at least 1");
  if (!(options.diffuse_variance_ratio > 0)) {
    throw InputError("fault analysis: the diffuse variance ratio must be positive");
  }
  const std::size_t nodes = result.positions.size() / 3;
  const std::size_t bonds = result.bonds.size() / 2;
  if (result.positions.size() % 3 != 0 || result.bonds.size() % 2 != 0) {
    throw InputError("the result's positions or bonds array has a partial row");
  }
  for (const std::int64_t node : result.bonds) {
    if (node < 0 || static_cast<std::size_t>(node) >= nodes) {
      throw InputError("the result has a bond to node " + std::to_string(node) + " of " +
                       std::to_string(nodes));
    }
  }
  const Snapshot& snapshot = result.snapshots[index];
  if (snapshot.bond_intact.size() != bonds || snapshot.displacement.size() != 3 * nodes) {
    throw InputError("snapshot " + std::to_string(index) + " has " +
                     std::to_string(snapshot.bond_intact.size()) + " bond states and " +
                     std::to_string(snapshot.displacement.size() / 3) + " displacements for " +
                     std::to_string(bonds) + " bonds and " + std::to_string(nodes) + " nodes");
  }
  for (const BreakEvent& event : result.events) {
    if (event.bond < 0 || static_cast<std::size_t>(event.bond) >= bonds) {
      throw InputError("the result has a break event for bond " + std::to_string(event.bond) +
                       " of " + std::to_string(bonds));
    }
  }
}

Point node_position(const RunResult& result, std::int64_t node) {
  return {result.positions[3 * node], result.positions[3 * node + 1],
          result.positions[3 * node + 2]};
}

// The break mode of each bond from its first event: 0 tensile, 1 shear, 2 pre-cut, -1 none.
std::vector<std::int8_t> break_modes(const RunResult& result) {
  std::vector<std::int8_t> modes(result.bonds.size() / 2, -1);
  for (const BreakEvent& event : result.events) {
    if (modes[event.bond] == -1) modes[event.bond] = event.mode;
  }
  return modes;
}

class DisjointSets final {
 public:
  explicit DisjointSets(std::size_t size) : parent_(size) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t root(std::size_t item) {
    while (parent_[item] != item) item = parent_[item] = parent_[parent_[item]];
    return item;
  }
  void join(std::size_t a, std::size_t b) {
    a = root(a);
    b = root(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

struct CellHash {
  std::size_t operator()(const std::array<std::int64_t, 3>& cell) const {
    std::uint64_t hash = 1469598103934665603ull;
    for (const std::int64_t c : cell)
      hash = (hash ^ static_cast<std::uint64_t>(c)) * 1099511628211ull;
    return static_cast<std::size_t>(hash);
  }
};

// Connected components of the graph linking points closer than `link`. Points are binned
// in cubic cells of edge `link`, so each point is compared only with those of the 27 cells
// around it: linear in the number of points.
std::vector<std::vector<std::size_t>> link_clusters(const std::vector<Point>& points, double link) {
  auto cell_of = [link](const Point& p) {
    return std::array<std::int64_t, 3>{static_cast<std::int64_t>(std::floor(p.x() / link)),
                                       static_cast<std::int64_t>(std::floor(p.y() / link)),
                                       static_cast<std::int64_t>(std::floor(p.z() / link))};
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::size_t>, CellHash> cells;
  for (std::size_t k = 0; k < points.size(); ++k) cells[cell_of(points[k])].push_back(k);

  DisjointSets sets(points.size());
  const double link_squared = link * link;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto home = cell_of(points[k]);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find({home[0] + dx, home[1] + dy, home[2] + dz});
          if (found == cells.end()) continue;
          for (const std::size_t other : found->second) {
            if (other > k && (points[other] - points[k]).squaredNorm() < link_squared) {
              sets.join(k, other);
            }
          }
        }
      }
    }
  }
  std::vector<std::vector<std::size_t>> clusters;
  std::vector<std::size_t> cluster_of_root(points.size(), points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::size_t root = sets.root(k);
    if (cluster_of_root[root] == points.size()) {
      cluster_of_root[root] = clusters.size();
      clusters.emplace_back();
    }
    clusters[cluster_of_root[root]].push_back(k);
  }
  return clusters;
}

double range_along(const std::vector<Point>& points, const Point& axis) {
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const Point& p : points) {
    low = std::min(low, p.dot(axis));
    high = std::max(high, p.dot(axis));
  }
  return high - low;
}

// Total least squares: the principal axes of the points' covariance. In 2-D the points lie
// in the x-z plane (y = 0) and the line runs along the largest axis; in 3-D the plane's
// normal is the smallest axis.
Fault fit_fault(const std::vector<Point>& points, int dim, double diffuse_ratio) {
  Fault fault;
  fault.bonds = static_cast<std::int64_t>(points.size());
  Point centroid = Point::Zero();
  for (const Point& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  std::vector<Point> centred;
  centred.reserve(points.size());
  for (const Point& p : points) centred.push_back(p - centroid);

  Point normal;
  if (dim == 2) {
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    for (const Point& p : centred) {
      const Eigen::Vector2d xz(p.x(), p.z());
      covariance += xz * xz.transpose();
    }
    covariance /= static_cast<double>(points.size());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance);
    const Eigen::Vector2d across = eigen.eigenvectors().col(0);
    const Eigen::Vector2d along = eigen.eigenvectors().col(1);
    normal = Point(across.x(), 0, across.y());
    const double largest = eigen.eigenvalues()(1);
    fault.variance_ratio = largest > 0 ? std::max(eigen.eigenvalues()(0), 0.0) / largest : 1.0;
    fault.extent = range_along(centred, Point(along.x(), 0, along.y()));
  } else {
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const Point& p : centred) covariance += p * p.transpose();
    covariance /= static_cast<double>(points.size());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    normal = eigen.eigenvectors().col(0);
    const double middle = eigen.eigenvalues()(1);
    fault.variance_ratio = middle > 0 ? std::max(eigen.eigenvalues()(0), 0.0) / middle : 1.0;
    fault.extent = range_along(centred, eigen.eigenvectors().col(1)) *
                   range_along(centred, eigen.eigenvectors().col(2));
  }
  if (normal.z() < 0 || (normal.z() == 0 && normal.x() < 0)) normal = -normal;
  normal.normalize();

  double squared_distance = 0;
  for (const Point& p : centred) squared_distance += std::pow(p.dot(normal), 2);
  fault.fit_rms = std::sqrt(squared_distance / static_cast<double>(points.size()));
  fault.centroid = {centroid.x(), centroid.y(), centroid.z()};
  fault.normal = {normal.x(), normal.y(), normal.z()};

  // The plane tilts its upward normal towards the side it descends to. The dip direction
  // along x is read from the trace in the x-z section, whose dip is atan(|nx| / nz).
  fault.dip_deg = std::atan2(std::hypot(normal.x(), normal.y()), normal.z()) / kDegree;
  fault.alpha_deg = 90.0 - fault.dip_deg;
  const double trace_dip_deg = std::atan2(std::abs(normal.x()), normal.z()) / kDegree;
  const bool level = fault.dip_deg < kLevelToleranceDeg ||
                     fault.dip_deg > 90.0 - kLevelToleranceDeg ||
                     trace_dip_deg < kLevelToleranceDeg;
  fault.dip_direction = level ? 0 : (normal.x() > 0 ? 1 : -1);
  fault.diffuse = !(fault.variance_ratio <= diffuse_ratio);
  return fault;
}

// Where the fault's trace in the x-z section at `y` meets the level z.
double trace_x(const Fault& fault, double y, double z) {
  const auto& n = fault.normal;
  const auto& c = fault.centroid;
  return c[0] - (n[1] * (y - c[1]) + n[2] * (z - c[2])) / n[0];
}

bool bounds_graben(const Fault& fault) {
  return !fault.diffuse && fault.dip_direction != 0 && fault.dip_deg >= kGrabenMinDipDeg &&
         fault.dip_deg <= kGrabenMaxDipDeg;
}

// Grabens: neighbouring inclined faults, ordered by where they reach the surface, of which
// the left one descends towards +x and the right one towards -x. Their traces then meet
// below the surface. The subsidence compares the top-row nodes between the two traces with
// those outside, leaving out a band of one spacing on each side of either trace.
std::vector<Graben> find_grabens(const RunResult& result, const Snapshot& snapshot,
                                 const std::vector<Fault>& faults) {
  const double spacing = result.scene.spacing;
  const std::size_t nodes = result.positions.size() / 3;
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < nodes; ++i) top = std::max(top, result.positions[3 * i + 2]);
  std::vector<std::size_t> surface;
  double mean_y = 0;
  for (std::size_t i = 0; i < nodes; ++i) {
    if (result.positions[3 * i + 2] >= top - spacing / 2) {
      surface.push_back(i);
      mean_y += result.positions[3 * i + 1];
    }
  }
  if (surface.empty()) return {};
  mean_y /= static_cast<double>(surface.size());

  std::vector<std::size_t> candidates;
  for (std::size_t f = 0; f < faults.size(); ++f) {
    if (bounds_graben(faults[f])) candidates.push_back(f);
  }
  std::sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
    return trace_x(faults[a], mean_y, top) < trace_x(faults[b], mean_y, top);
  });

  std::vector<Graben> grabens;
  for (std::size_t k = 0; k + 1 < candidates.size(); ++k) {
    const Fault& left = faults[candidates[k]];
    const Fault& right = faults[candidates[k + 1]];
    if (left.dip_direction != 1 || right.dip_direction != -1) continue;
    Graben graben;
    graben.left_fault = candidates[k];
    graben.right_fault = candidates[k + 1];
    graben.left_surface_x = trace_x(left, mean_y, top);
    graben.right_surface_x = trace_x(right, mean_y, top);
    // Both traces descend inwards, so they meet below the surface at depth d where their
    // horizontal gap closes: gap = d (cot dip_left + cot dip_right) in the x-z section.
    const double closing =
        left.normal[2] / std::abs(left.normal[0]) + right.normal[2] / std::abs(right.normal[0]);
    graben.apex_depth = (graben.right_surface_x - graben.left_surface_x) / closing;

    double inside_sum = 0, outside_sum = 0;
    std::int64_t inside = 0, outside = 0;
    for (const std::size_t i : surface) {
      const double x = result.positions[3 * i];
      const double y = result.positions[3 * i + 1];
      const double z = result.positions[3 * i + 2];
      const double x_left = trace_x(left, y, z);
      const double x_right = trace_x(right, y, z);
      const double uz = snapshot.displacement[3 * i + 2];
      if (x > x_left + spacing && x < x_right - spacing) {
        inside_sum += uz;
        ++inside;
      } else if (x < x_left - spacing || x > x_right + spacing) {
        outside_sum += uz;
        ++outside;
      }
    }
    graben.surface_subsidence = inside > 0 && outside > 0
                                    ? outside_sum / outside - inside_sum / inside
                                    : std::numeric_limits<double>::quiet_NaN();
    grabens.push_back(graben);
  }
  return grabens;
}

}  // namespace

FaultReport analyze_faults(const RunResult& result, std::size_t index,
                           const FaultOptions& options) {
  if (index == kLastSnapshot && !result.snapshots.empty()) index = result.snapshots.size() - 1;
  check_input(result, index, options);
  const Snapshot& snapshot = result.snapshots[index];
  const int dim = result.scene.dim;

  FaultReport report;
  report.dim = dim;
  report.lambda = snapshot.lambda;
  const std::vector<std::int8_t> modes = break_modes(result);
  std::vector<std::int64_t> broken;
  std::vector<Point> midpoints;
  for (std::size_t b = 0; b < snapshot.bond_intact.size(); ++b) {
    if (snapshot.bond_intact[b] != 0 || modes[b] == 2) continue;
    broken.push_back(static_cast<std::int64_t>(b));
    midpoints.push_back(0.5 * (node_position(result, result.bonds[2 * b]) +
                               node_position(result, result.bonds[2 * b + 1])));
    if (dim == 2) midpoints.back().y() = 0;
  }
  report.broken_bonds = static_cast<std::int64_t>(broken.size());

  const double link = options.link_distance_spacings * result.scene.spacing;
  for (const std::vector<std::size_t>& cluster : link_clusters(midpoints, link)) {
    if (static_cast<std::int64_t>(cluster.size()) < options.min_bonds) continue;
    std::vector<Point> points;
    std::int64_t tensile = 0, shear = 0;
    for (const std::size_t k : cluster) {
      points.push_back(midpoints[k]);
      tensile += modes[broken[k]] == 0;
      shear += modes[broken[k]] == 1;
    }
    Fault fault = fit_fault(points, dim, options.diffuse_variance_ratio);
    fault.diffuse =
        fault.diffuse || fault.fit_rms > options.diffuse_rms_spacings * result.scene.spacing;
    fault.tensile_share = static_cast<double>(tensile) / static_cast<double>(cluster.size());
    fault.shear_share = static_cast<double>(shear) / static_cast<double>(cluster.size());
    report.faults.push_back(fault);
  }
  std::sort(report.faults.begin(), report.faults.end(), [](const Fault& a, const Fault& b) {
    if (a.bonds != b.bonds) return a.bonds > b.bonds;
    return a.centroid < b.centroid;
  });
  report.grabens = find_grabens(result, snapshot, report.faults);
  return report;
}

}  // namespace latfrac
