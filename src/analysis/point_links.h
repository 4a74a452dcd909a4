// Links between points closer than a distance, and the connected clusters they form.
//
// The fault analysis links the midpoints of broken bonds this way to find its clusters, and
// the cluster splitter to keep each part of a split cluster connected.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace latfrac {

// The links between points closer than `link` (m). Points are binned in cubic cells of edge
// `link`, so each point is compared only with those of the 27 cells around it: linear in the
// number of points.
class LinkGrid final {
 public:
  // Keeps a reference to `points`, which must outlive the grid.
  LinkGrid(const std::vector<Eigen::Vector3d>& points, double link);

  // Calls visit(other) for every other point closer than the link distance to point k.
  template <class Visit>
  void for_each_linked(std::size_t k, Visit&& visit) const {
    const Cell home = cell_of(points_[k]);
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
  struct CellHash {
    std::size_t operator()(const Cell& cell) const;
  };
  Cell cell_of(const Eigen::Vector3d& p) const;

  const std::vector<Eigen::Vector3d>& points_;
  double link_;  // m
  std::unordered_map<Cell, std::vector<std::size_t>, CellHash> cells_;
};

// The same links as lists, for the many passes over one cluster's links that splitting it
// makes: the grid's hash lookups are paid once. A cluster has far fewer than 2^32 points.
class LinkGraph final {
 public:
  LinkGraph(const std::vector<Eigen::Vector3d>& points, double link);

  template <class Visit>
  void for_each_linked(std::size_t k, Visit&& visit) const {
    for (std::size_t i = offsets_[k]; i < offsets_[k + 1]; ++i) visit(std::size_t{linked_[i]});
  }

 private:
  std::vector<std::size_t> offsets_;
  std::vector<std::uint32_t> linked_;
};

class DisjointSets final {
 public:
  explicit DisjointSets(std::size_t size);
  std::size_t root(std::size_t item);
  void join(std::size_t a, std::size_t b);

 private:
  std::vector<std::size_t> parent_;
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

}  // namespace latfrac
