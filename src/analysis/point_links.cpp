// Links between points closer than a distance, and the connected clusters they form.
#include "point_links.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace latfrac {

LinkGrid::LinkGrid(const std::vector<Eigen::Vector3d>& points, double link)
    : points_(points), link_(link) {
  for (std::size_t k = 0; k < points.size(); ++k) cells_[cell_of(points[k])].push_back(k);
}

std::size_t LinkGrid::CellHash::operator()(const Cell& cell) const {
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
  for (const std::int64_t c : cell)
    hash = (hash ^ static_cast<std::uint64_t>(c)) * 1099511628211ull;
  return static_cast<std::size_t>(hash);
}

LinkGrid::Cell LinkGrid::cell_of(const Eigen::Vector3d& p) const {
  return {static_cast<std::int64_t>(std::floor(p.x() / link_)),
          static_cast<std::int64_t>(std::floor(p.y() / link_)),
          static_cast<std::int64_t>(std::floor(p.z() / link_))};
}

LinkGraph::LinkGraph(const std::vector<Eigen::Vector3d>& points, double link)
    : offsets_(points.size() + 1, 0) {
  const LinkGrid grid(points, link);
  for (std::size_t k = 0; k < points.size(); ++k) {
    grid.for_each_linked(
        k, [&](std::size_t other) { linked_.push_back(static_cast<std::uint32_t>(other)); });
    offsets_[k + 1] = linked_.size();
  }
}

DisjointSets::DisjointSets(std::size_t size) : parent_(size) {
  std::iota(parent_.begin(), parent_.end(), std::size_t{0});
}

std::size_t DisjointSets::root(std::size_t item) {
  while (parent_[item] != item) item = parent_[item] = parent_[parent_[item]];
  return item;
}

void DisjointSets::join(std::size_t a, std::size_t b) {
  a = root(a);
  b = root(b);
  if (a != b) parent_[std::max(a, b)] = std::min(a, b);
}

}  // namespace latfrac
