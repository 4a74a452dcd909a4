// Fault analysis: clusters of broken bonds, their fitted lines or planes, and grabens.
#include "latfrac/fault_analysis.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
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
  if (!(options.split_rms_spacings > 0)) {
    throw InputError("fault analysis: the split rms must be positive (spacings)");
  }
  if (options.max_split_depth < 0) {
    throw InputError("fault analysis: max_split_depth must be 0 (never split) or more");
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

// The links between points closer than `link`. Points are binned in cubic cells of edge
// `link`, so each point is compared only with those of the 27 cells around it: linear in the
// number of points.
class LinkGrid final {
 public:
  LinkGrid(const std::vector<Point>& points, double link) : points_(points), link_(link) {
    for (std::size_t k = 0; k < points.size(); ++k) cells_[cell_of(points[k])].push_back(k);
  }

  // Calls visit(other) for every other point closer than the link distance to point k.
  template <class Visit>
  void for_each_linked(std::size_t k, Visit&& visit) const {
    const auto home = cell_of(points_[k]);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto found = cells_.find({home[0] + dx, home[1] + dy, home[2] + dz});
          if (found == cells_.end()) continue;
          for (const std::size_t other : found->second) {
            if (other != k && (points_[other] - points_[k]).squaredNorm() < link_ * link_) {
              visit(other);
            }
          }
        }
      }
    }
  }

 private:
  using Cell = std::array<std::int64_t, 3>;
  Cell cell_of(const Point& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / link_)),
            static_cast<std::int64_t>(std::floor(p.y() / link_)),
            static_cast<std::int64_t>(std::floor(p.z() / link_))};
  }

  const std::vector<Point>& points_;
  double link_;
  std::unordered_map<Cell, std::vector<std::size_t>, CellHash> cells_;
};

// The same links as lists, for the many passes over one cluster's links that splitting it
// makes: the grid's hash lookups are paid once. A cluster has far fewer than 2^32 points.
class LinkGraph final {
 public:
  LinkGraph(const std::vector<Point>& points, double link) : offsets_(points.size() + 1, 0) {
    const LinkGrid grid(points, link);
    for (std::size_t k = 0; k < points.size(); ++k) {
      grid.for_each_linked(
          k, [&](std::size_t other) { linked_.push_back(static_cast<std::uint32_t>(other)); });
      offsets_[k + 1] = linked_.size();
    }
  }

  template <class Visit>
  void for_each_linked(std::size_t k, Visit&& visit) const {
    for (std::size_t i = offsets_[k]; i < offsets_[k + 1]; ++i) visit(std::size_t{linked_[i]});
  }

 private:
  std::vector<std::size_t> offsets_;
  std::vector<std::uint32_t> linked_;
};

// Connected components of the links (a LinkGrid or a LinkGraph) between points of the same
// group (group[k] for point k), each listed in increasing point order, in the order of their
// first points.
template <class Links>
std::vector<std::vector<std::size_t>> link_components(const Links& links,
                                                      const std::vector<int>& group) {
  DisjointSets sets(group.size());
  for (std::size_t k = 0; k < group.size(); ++k) {
    links.for_each_linked(k, [&](std::size_t other) {
      if (other > k && group[other] == group[k]) sets.join(k, other);
    });
  }
  std::vector<std::vector<std::size_t>> components;
  std::vector<std::size_t> component_of_root(group.size(), group.size());
  for (std::size_t k = 0; k < group.size(); ++k) {
    const std::size_t root = sets.root(k);
    if (component_of_root[root] == group.size()) {
      component_of_root[root] = components.size();
      components.emplace_back();
    }
    components[component_of_root[root]].push_back(k);
  }
  return components;
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

// The principal axes of the points k with select(k): the eigenvectors of their covariance
// about their centroid. In 2-D the points lie in the x-z plane (y = 0) and there are two.
struct PrincipalAxes {
  std::size_t count = 0;
  Point centroid = Point::Zero();
  std::vector<Point> axes;        // unit vectors, smallest variance first
  std::vector<double> variances;  // m^2, ascending
};

template <class Select>
PrincipalAxes principal_axes(const std::vector<Point>& points, int dim, Select&& select) {
  PrincipalAxes principal;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!select(k)) continue;
    principal.centroid += points[k];
    ++principal.count;
  }
  if (principal.count == 0) return principal;
  principal.centroid /= static_cast<double>(principal.count);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!select(k)) continue;
    const Point d = points[k] - principal.centroid;
    covariance += d * d.transpose();
  }
  covariance /= static_cast<double>(principal.count);
  if (dim == 2) {
    Eigen::Matrix2d xz;
    xz << covariance(0, 0), covariance(0, 2), covariance(2, 0), covariance(2, 2);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(xz);
    for (int i = 0; i < 2; ++i) {
      principal.axes.emplace_back(eigen.eigenvectors()(0, i), 0, eigen.eigenvectors()(1, i));
      principal.variances.push_back(eigen.eigenvalues()(i));
    }
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    for (int i = 0; i < 3; ++i) {
      principal.axes.emplace_back(eigen.eigenvectors().col(i));
      principal.variances.push_back(eigen.eigenvalues()(i));
    }
  }
  return principal;
}

// Total least squares: the principal axes of the points' covariance. In 2-D the line runs
// along the largest axis; in 3-D the plane's normal is the smallest axis. diffuse_rms in m.
Fault fit_fault(const std::vector<Point>& points, int dim, double diffuse_ratio,
                double diffuse_rms) {
  const PrincipalAxes principal = principal_axes(points, dim, [](std::size_t) { return true; });
  Fault fault;
  fault.bonds = static_cast<std::int64_t>(points.size());
  // 2-D: second / first variance; 3-D: smallest / middle. Both are variances[0] / [1].
  const double reference = principal.variances[1];
  fault.variance_ratio = reference > 0 ? std::max(principal.variances[0], 0.0) / reference : 1.0;
  fault.extent =
      dim == 2 ? range_along(points, principal.axes[1])
               : range_along(points, principal.axes[1]) * range_along(points, principal.axes[2]);
  Point normal = principal.axes[0];
  if (normal.z() < 0 || (normal.z() == 0 && normal.x() < 0)) normal = -normal;
  normal.normalize();

  double squared_distance = 0;
  for (const Point& p : points)
    squared_distance += std::pow((p - principal.centroid).dot(normal), 2);
  fault.fit_rms = std::sqrt(squared_distance / static_cast<double>(points.size()));
  fault.centroid = {principal.centroid.x(), principal.centroid.y(), principal.centroid.z()};
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
  fault.diffuse = !(fault.variance_ratio <= diffuse_ratio) || fault.fit_rms > diffuse_rms;
  return fault;
}

// Lines (2-D) or planes (3-D) fitted to groups of points: k-lines (k-planes). From the seed
// labels (0 .. flats - 1 per point) it alternates a total-least-squares fit of each group
// with moving every point to the flat nearest to it (a tie keeps its group). Both steps lower
// the sum of squared distances, so it settles, in a few sweeps in practice. Returns false when
// a group becomes too small to fit.
bool fit_flats(const std::vector<Point>& points, int dim, int flats, std::vector<int>& labels) {
  constexpr int kMaxSweeps = 50;
  std::vector<Point> centroids(flats), normals(flats);
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    for (int group = 0; group < flats; ++group) {
      const PrincipalAxes principal =
          principal_axes(points, dim, [&](std::size_t k) { return labels[k] == group; });
      if (principal.count < static_cast<std::size_t>(dim)) return false;
      centroids[group] = principal.centroid;
      normals[group] = principal.axes[0];
    }
    bool moved = false;
    for (std::size_t k = 0; k < points.size(); ++k) {
      int nearest = labels[k];
      double nearest_distance = std::abs((points[k] - centroids[nearest]).dot(normals[nearest]));
      for (int group = 0; group < flats; ++group) {
        const double distance = std::abs((points[k] - centroids[group]).dot(normals[group]));
        if (distance < nearest_distance) {
          nearest = group;
          nearest_distance = distance;
        }
      }
      moved = moved || nearest != labels[k];
      labels[k] = nearest;
    }
    if (!moved) break;
  }
  return true;
}

// Splits a cluster that one line or plane does not fit (faults that touch: a V, a Y, a
// zigzag) into straight faults; docs/fault-analysis.md, "Branched clusters", gives the rule.
// Clusters and parts are lists of indices into the midpoints.
class ClusterSplitter final {
 public:
  using Parts = std::vector<std::vector<std::size_t>>;

  ClusterSplitter(const std::vector<Point>& midpoints, int dim, const FaultOptions& options,
                  double spacing)
      : midpoints_(midpoints),
        dim_(dim),
        options_(options),
        spacing_(spacing),
        min_part_(
            std::max<std::size_t>(static_cast<std::size_t>(options.min_bonds), kMinPartBonds)) {}

  // The cluster's faults: its straight parts if it resolves into parts that are all faults,
  // else the whole cluster.
  Parts split(const std::vector<std::size_t>& cluster) const {
    Parts parts = resolve(cluster, 0);
    if (parts.empty()) return {cluster};
    return parts.size() > 1 ? rejoin(cluster, std::move(parts)) : parts;
  }

  Fault fit(const std::vector<std::size_t>& members) const { return fit(gather(members)); }

 private:
  // Parts must fit this much better (rms) than the whole. Halving a uniform thick band
  // lengthwise gives 0.5, a V or a Y of thin arms about 0.1.
  static constexpr double kSplitGain = 0.5;
  // Touching parts closer than this in angle are one thick fault cut lengthwise, or one
  // fault cut across, not two faults.
  static constexpr double kMinSplitAngleDeg = 10.0;
  // A part needs at least min_bonds points, and this many and this share of the points
  // divided: fewer say little about a fault's dip, and the pieces cut off where two faults
  // meet are smaller.
  static constexpr std::size_t kMinPartBonds = 10;
  static constexpr double kMinPartShare = 0.05;

  std::vector<Point> gather(const std::vector<std::size_t>& members) const {
    std::vector<Point> points;
    points.reserve(members.size());
    for (const std::size_t m : members) points.push_back(midpoints_[m]);
    return points;
  }

  Fault fit(const std::vector<Point>& points) const {
    return fit_fault(points, dim_, options_.diffuse_variance_ratio,
                     options_.diffuse_rms_spacings * spacing_);
  }

  bool well_fitted(const Fault& fault) const {
    return !fault.diffuse && fault.fit_rms <= options_.split_rms_spacings * spacing_;
  }

  static bool meet_at_small_angle(const Fault& a, const Fault& b) {
    const double cosine =
        a.normal[0] * b.normal[0] + a.normal[1] * b.normal[1] + a.normal[2] * b.normal[2];
    return std::abs(cosine) > std::cos(kMinSplitAngleDeg * kDegree);
  }

  // A division may cut across one straight fault (dividing a W in halves cuts its middle
  // arms), so that its pieces end in different parts. Touching parts that meet at less than
  // kMinSplitAngleDeg are joined again when the joined part is well fitted, first pair first.
  Parts rejoin(const std::vector<std::size_t>& cluster, Parts parts) const {
    const std::vector<Point> points = gather(cluster);  // cluster is in increasing order
    std::vector<std::size_t> owner(cluster.size());
    for (std::size_t p = 0; p < parts.size(); ++p) {
      for (const std::size_t m : parts[p]) {
        owner[std::lower_bound(cluster.begin(), cluster.end(), m) - cluster.begin()] = p;
      }
    }
    std::set<std::pair<std::size_t, std::size_t>> touching;
    const LinkGrid grid(points, options_.link_distance_spacings * spacing_);
    for (std::size_t k = 0; k < points.size(); ++k) {
      grid.for_each_linked(k, [&](std::size_t other) {
        if (owner[k] < owner[other]) touching.insert({owner[k], owner[other]});
      });
    }
    std::vector<Fault> fits;
    for (const std::vector<std::size_t>& part : parts) fits.push_back(fit(part));
    for (bool joined = true; joined;) {
      joined = false;
      for (const auto& [a, b] : touching) {
        if (!meet_at_small_angle(fits[a], fits[b])) continue;
        std::vector<std::size_t> both = parts[a];
        both.insert(both.end(), parts[b].begin(), parts[b].end());
        std::sort(both.begin(), both.end());
        const Fault joined_fit = fit(both);
        if (!well_fitted(joined_fit)) continue;
        parts[a] = std::move(both);
        fits[a] = joined_fit;
        parts[b].clear();
        std::set<std::pair<std::size_t, std::size_t>> renamed;
        for (auto [c, d] : touching) {
          if (c == b) c = a;
          if (d == b) d = a;
          if (c != d) renamed.insert({std::min(c, d), std::max(c, d)});
        }
        touching = std::move(renamed);
        joined = true;
        break;
      }
    }
    std::erase_if(parts, [](const std::vector<std::size_t>& part) { return part.empty(); });
    return parts;
  }

  // The members as faults that are not diffuse, found within max_split_depth - depth more
  // levels of splitting; empty when they do not resolve into such faults.
  Parts resolve(const std::vector<std::size_t>& members, int depth) const {
    const Fault whole = fit(members);
    const Parts unsplit = whole.diffuse ? Parts{} : Parts{members};
    if (well_fitted(whole) || depth >= options_.max_split_depth) return unsplit;
    const Parts parts = divide(members, whole.fit_rms);
    if (parts.empty()) return unsplit;
    Parts resolved;
    for (const std::vector<std::size_t>& part : parts) {
      Parts pieces = resolve(part, depth + 1);
      if (pieces.empty()) return unsplit;
      for (std::vector<std::size_t>& piece : pieces) resolved.push_back(std::move(piece));
    }
    return resolved;
  }

  // The members divided between lines or planes, as connected parts; empty when no division
  // passes. Every seed gives a division into two or more parts (a zigzag gives three). The
  // best passing division with the fewest parts is kept, unless one with more parts fits
  // better by the same gain that a division needs over the whole. whole_rms: the members'
  // rms about their own fit, m.
  Parts divide(const std::vector<std::size_t>& members, double whole_rms) const {
    const std::vector<Point> points = gather(members);
    const LinkGraph links(points, options_.link_distance_spacings * spacing_);
    std::map<std::size_t, std::pair<double, Parts>> best_by_count;  // parts -> (rms m, parts)
    for (const int flats : {2, 3}) {
      for (std::vector<int>& labels : seeds(points, flats)) {
        if (!fit_flats(points, dim_, flats, labels)) continue;
        double rms = 0;
        Parts parts = polished_parts(points, links, labels, rms);
        if (parts.empty()) continue;
        const std::size_t count = parts.size();
        const auto best = best_by_count.find(count);
        if (best == best_by_count.end() || rms < best->second.first) {
          best_by_count[count] = {rms, std::move(parts)};
        }
      }
    }
    Parts chosen;
    double required_rms = kSplitGain * whole_rms;  // m
    for (auto& [count, best] : best_by_count) {
      if (!(best.first < required_rms)) continue;
      chosen = std::move(best.second);
      required_rms = kSplitGain * best.first;
    }
    for (std::vector<std::size_t>& part : chosen) {
      for (std::size_t& k : part) k = members[k];
    }
    return chosen;
  }

  // The parts of a division by k-flats labels (connected_parts), polished: refitted with one
  // flat per part. A group's flat is infinite, so it can take the end of another fault where
  // it passes near it (the corners of a zigzag); a flat per part gives those points back.
  // Polishing keeps the number of parts: only the largest piece of each part's group stays a
  // part. rms: the parts' pooled rms, m.
  Parts polished_parts(const std::vector<Point>& points, const LinkGraph& links,
                       const std::vector<int>& labels, double& rms) const {
    Parts parts = connected_parts(points, links, labels, rms, kEveryLargePiece);
    if (parts.empty()) return parts;
    std::vector<int> part_labels(points.size());
    for (std::size_t p = 0; p < parts.size(); ++p) {
      for (const std::size_t k : parts[p]) part_labels[k] = static_cast<int>(p);
    }
    if (!fit_flats(points, dim_, static_cast<int>(parts.size()), part_labels)) return parts;
    double polished_rms = 0;
    Parts polished = connected_parts(points, links, part_labels, polished_rms, kLargestPieceOnly);
    if (polished.empty() || polished_rms > rms) return parts;
    rms = polished_rms;
    return polished;
  }

  // Seed labels for k-flats with two or three flats, from the points' principal axes. Two:
  // the points beyond the 1/4, 1/2 or 3/4 quantile along each axis (one of these separates
  // the arms of a V or a Y), or those whose coordinates along two axes have the same sign
  // (the arms of an X). Three: the thirds along each axis (the segments of a zigzag).
  std::vector<std::vector<int>> seeds(const std::vector<Point>& points, int flats) const {
    const std::size_t count = points.size();
    const PrincipalAxes principal = principal_axes(points, dim_, [](std::size_t) { return true; });
    std::vector<std::vector<double>> along;  // coordinates along each axis, m
    for (const Point& axis : principal.axes) {
      along.emplace_back(count);
      for (std::size_t k = 0; k < count; ++k) {
        along.back()[k] = (points[k] - principal.centroid).dot(axis);
      }
    }
    const std::vector<std::vector<double>> quantile_sets =
        flats == 2 ? std::vector<std::vector<double>>{{0.25}, {0.5}, {0.75}}
                   : std::vector<std::vector<double>>{{1.0 / 3, 2.0 / 3}};
    std::vector<std::vector<int>> seeds;
    for (const std::vector<double>& coordinates : along) {
      std::vector<double> sorted = coordinates;
      std::sort(sorted.begin(), sorted.end());
      for (const std::vector<double>& quantiles : quantile_sets) {
        std::vector<int>& labels = seeds.emplace_back(count, 0);
        for (const double quantile : quantiles) {
          const double cut = sorted[static_cast<std::size_t>(quantile * (count - 1))];
          for (std::size_t k = 0; k < count; ++k) labels[k] += coordinates[k] > cut;
        }
      }
    }
    if (flats == 2) {
      for (std::size_t a = 0; a < along.size(); ++a) {
        for (std::size_t b = a + 1; b < along.size(); ++b) {
          std::vector<int>& labels = seeds.emplace_back(count, 0);
          for (std::size_t k = 0; k < count; ++k) labels[k] = along[a][k] * along[b][k] > 0;
        }
      }
    }
    return seeds;
  }

  // The parts of a division by labels, as lists of indices into points, and their pooled rms
  // distance from their own fits (m). Each group's connected pieces that are large enough
  // are the parts (with kLargestPieceOnly, only the largest piece of each group, the first
  // of equals). The other pieces are crumbs: they join the part that reaches them first
  // through the links (breadth first), so every part stays connected and every point is
  // kept. Empty when there are fewer than two parts, or when two touching parts meet at less
  // than kMinSplitAngleDeg.
  enum PieceRule { kEveryLargePiece, kLargestPieceOnly };
  Parts connected_parts(const std::vector<Point>& points, const LinkGraph& links,
                        const std::vector<int>& labels, double& rms, PieceRule rule) const {
    constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
    std::vector<std::size_t> owner(points.size(), kNone);
    std::vector<std::size_t> frontier;
    const std::size_t min_part =
        std::max(min_part_, static_cast<std::size_t>(std::ceil(kMinPartShare * points.size())));
    std::vector<std::vector<std::size_t>> pieces = link_components(links, labels);
    if (rule == kLargestPieceOnly) {
      // Pieces are in the order of their first points, so the first largest is well defined.
      std::unordered_map<int, std::size_t> largest;  // group -> index of its largest piece
      for (std::size_t p = 0; p < pieces.size(); ++p) {
        const auto [found, fresh] = largest.try_emplace(labels[pieces[p].front()], p);
        if (!fresh && pieces[p].size() > pieces[found->second].size()) found->second = p;
      }
      for (std::size_t p = 0; p < pieces.size(); ++p) {
        if (largest.at(labels[pieces[p].front()]) != p) pieces[p].clear();
      }
    }
    std::size_t part_count = 0;
    for (const std::vector<std::size_t>& piece : pieces) {
      if (piece.empty() || piece.size() < min_part) continue;
      for (const std::size_t k : piece) {
        owner[k] = part_count;
        frontier.push_back(k);
      }
      ++part_count;
    }
    if (part_count < 2) return {};
    for (std::size_t next = 0; next < frontier.size(); ++next) {
      const std::size_t k = frontier[next];
      links.for_each_linked(k, [&](std::size_t other) {
        if (owner[other] != kNone) return;
        owner[other] = owner[k];
        frontier.push_back(other);
      });
    }
    assert(frontier.size() == points.size());  // the points are connected
    Parts parts(part_count);
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (owner[k] != kNone) parts[owner[k]].push_back(k);
    }

    std::vector<Fault> fits;
    double squared_distance = 0;
    for (const std::vector<std::size_t>& part : parts) {
      std::vector<Point> part_points;
      for (const std::size_t k : part) part_points.push_back(points[k]);
      fits.push_back(fit(part_points));
      squared_distance += std::pow(fits.back().fit_rms, 2) * static_cast<double>(part.size());
    }
    rms = std::sqrt(squared_distance / static_cast<double>(points.size()));
    for (std::size_t k = 0; k < points.size(); ++k) {
      bool too_parallel = false;
      links.for_each_linked(k, [&](std::size_t other) {
        const std::size_t a = owner[k], b = owner[other];
        too_parallel = too_parallel || (a != b && meet_at_small_angle(fits[a], fits[b]));
      });
      if (too_parallel) return {};
    }
    return parts;
  }

  const std::vector<Point>& midpoints_;
  int dim_;
  FaultOptions options_;
  double spacing_;  // m
  std::size_t min_part_;
};

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
// below the surface, and both faults must lie above that point. The subsidence compares the
// top-row nodes between the two traces with those outside, leaving out a band of one spacing
// on each side of either trace.
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
    // The faults must lie above the point where their traces meet. Two faults below it, such
    // as the arms of an inverted V, dip away from each other where they exist: no graben.
    const double apex_z = top - graben.apex_depth;
    if (!(left.centroid[2] > apex_z && right.centroid[2] > apex_z)) continue;

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

  const LinkGrid grid(midpoints, options.link_distance_spacings * result.scene.spacing);
  const ClusterSplitter splitter(midpoints, dim, options, result.scene.spacing);
  for (const std::vector<std::size_t>& cluster :
       link_components(grid, std::vector<int>(midpoints.size(), 0))) {
    if (static_cast<std::int64_t>(cluster.size()) < options.min_bonds) continue;
    for (const std::vector<std::size_t>& part : splitter.split(cluster)) {
      Fault fault = splitter.fit(part);
      std::int64_t tensile = 0, shear = 0;
      for (const std::size_t k : part) {
        tensile += modes[broken[k]] == 0;
        shear += modes[broken[k]] == 1;
      }
      fault.tensile_share = static_cast<double>(tensile) / static_cast<double>(part.size());
      fault.shear_share = static_cast<double>(shear) / static_cast<double>(part.size());
      report.faults.push_back(fault);
    }
  }
  std::sort(report.faults.begin(), report.faults.end(), [](const Fault& a, const Fault& b) {
    if (a.bonds != b.bonds) return a.bonds > b.bonds;
    return a.centroid < b.centroid;
  });
  report.grabens = find_grabens(result, snapshot, report.faults);
  return report;
}

}  // namespace latfrac
