// Finding parts of the body without support, and holding them.
#include "latfrac/mechanics/fragments.h"

#include <algorithm>
#include <deque>

#include "latfrac/base/error.h"

namespace latfrac {

FragmentDetector::FragmentDetector(const Model& model) : neighbours_(model.lattice.node_count()) {
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    const Bond& bond = model.lattice.bonds[b];
    neighbours_[bond.i].push_back({bond.j, b});
    neighbours_[bond.j].push_back({bond.i, b});
  }
}

namespace {

bool carries(const Model& model, std::int64_t bond) { return connects(model.state(bond)); }

}  // namespace

// Do the bond's two nodes still meet? Two searches grow in turn from either end, so the
// cost is that of the smaller side when they do not, and small when they meet nearby.
bool FragmentDetector::connects(const Model& model, std::int64_t bond) const {
  const Bond& pair = model.lattice.bonds[bond];
  std::vector<std::int8_t> side(model.lattice.node_count(), 0);
  std::deque<std::int64_t> frontier[2];
  side[pair.i] = 1;
  side[pair.j] = 2;
  frontier[0].push_back(pair.i);
  frontier[1].push_back(pair.j);
  while (!frontier[0].empty() && !frontier[1].empty()) {
    for (int s = 0; s < 2; ++s) {
      const std::int64_t node = frontier[s].front();
      frontier[s].pop_front();
      for (const auto& [next, b] : neighbours_[node]) {
        if (!carries(model, b)) continue;
        if (side[next] == 0) {
          side[next] = static_cast<std::int8_t>(s + 1);
          frontier[s].push_back(next);
        } else if (side[next] != s + 1) {
          return true;
        }
      }
      if (frontier[s].empty()) return false;
    }
  }
  return false;
}

std::vector<std::int64_t> FragmentDetector::component(const Model& model,
                                                      std::int64_t start) const {
  std::vector<std::uint8_t> seen(model.lattice.node_count(), 0);
  std::vector<std::int64_t> nodes{start};
  seen[start] = 1;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    for (const auto& [next, b] : neighbours_[nodes[k]]) {
      if (seen[next] || !carries(model, b)) continue;
      seen[next] = 1;
      nodes.push_back(next);
    }
  }
  return nodes;
}

std::vector<int> FragmentDetector::free_components(const Model& model,
                                                   const std::vector<std::int64_t>& nodes) const {
  const int dim = model.dim();
  std::vector<int> free;
  for (int c = 0; c < dim; ++c) {
    const bool held = std::any_of(nodes.begin(), nodes.end(), [&](std::int64_t node) {
      return model.dofs().free_index[node * dim + c] < 0;
    });
    if (!held) free.push_back(c);
  }
  return free;
}

std::vector<FragmentDetector::LoosePart> FragmentDetector::unsupported_after_break(
    const Model& model, std::int64_t bond) const {
  if (connects(model, bond)) return {};
  std::vector<LoosePart> loose;
  for (std::int64_t end : {model.lattice.bonds[bond].i, model.lattice.bonds[bond].j}) {
    LoosePart part{component(model, end), {}};
    part.free_components = free_components(model, part.nodes);
    if (!part.free_components.empty()) loose.push_back(std::move(part));
  }
  return loose;
}

std::vector<FragmentDetector::LoosePart> FragmentDetector::unsupported_parts(
    const Model& model) const {
  std::vector<std::uint8_t> seen(model.lattice.node_count(), 0);
  std::vector<LoosePart> loose;
  for (std::int64_t start = 0; start < model.lattice.node_count(); ++start) {
    if (seen[start]) continue;
    LoosePart part{component(model, start), {}};
    for (std::int64_t node : part.nodes) seen[node] = 1;
    part.free_components = free_components(model, part.nodes);
    if (!part.free_components.empty()) loose.push_back(std::move(part));
  }
  return loose;
}

}  // namespace latfrac
