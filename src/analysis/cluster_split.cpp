// Splits a cluster of broken bonds that one line or plane does not fit into straight faults.
#include "cluster_split.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

#include "point_links.h"

namespace latfrac {

namespace {

using Point = Eigen::Vector3d;

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

// The splitting rule of docs/fault-analysis.md, "Splitting branched clusters". Clusters
// and parts are lists of indices into the midpoints.
class ClusterSplitter final {
 public:
  using Parts = std::vector<std::vector<std::size_t>>;

  ClusterSplitter(const std::vector<Point>& midpoints, const FaultFitter& fitter,
                  const FaultOptions& options, double spacing)
      : midpoints_(midpoints),
        fitter_(fitter),
        dim_(fitter.dim()),
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

  Fault fit(const std::vector<std::size_t>& members) const { return fit(gather(members)); }
  Fault fit(const std::vector<Point>& points) const { return fitter_.fit(points); }

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
  const FaultFitter& fitter_;
  int dim_;
  FaultOptions options_;
  double spacing_;  // m
  std::size_t min_part_;
};

}  // namespace

std::vector<std::vector<std::size_t>> split_cluster(const std::vector<Eigen::Vector3d>& midpoints,
                                                    const std::vector<std::size_t>& cluster,
                                                    const FaultFitter& fitter,
                                                    const FaultOptions& options, double spacing) {
  return ClusterSplitter(midpoints, fitter, options, spacing).split(cluster);
}

}  // namespace latfrac
