// Grabens: pairs of inclined faults that bound a block, and the subsidence of that block.
#include "grabens.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>
#include <utility>

namespace latfrac {

namespace {

// Faults that may bound a graben: inclined, neither near vertical nor near horizontal.
constexpr double kGrabenMinDipDeg = 20.0;
constexpr double kGrabenMaxDipDeg = 80.0;

// Where the fault's trace in the x-z section at `y` meets the level z.
double trace_x(const Fault& fault, double y, double z) {
  const auto& n = fault.normal;
  const auto& c = fault.centroid;
  return c[0] - (n[1] * (y - c[1]) + n[2] * (z - c[2])) / n[0];
}

bool bounds_graben(const Fault& fault, const FaultOptions& options) {
  return !fault.diffuse && fault.dip_direction != 0 && fault.dip_deg >= kGrabenMinDipDeg &&
         fault.dip_deg <= kGrabenMaxDipDeg && fault.wall_share < options.wall_share;
}

// The top of the lattice and its surface nodes (within half a spacing of the top).
struct Surface {
  double top = -std::numeric_limits<double>::infinity();  // m
  double mean_y = 0;                                      // m
  std::vector<std::size_t> nodes;
};

Surface surface_of(const RunResult& result) {
  Surface surface;
  const std::size_t nodes = result.positions.size() / 3;
  for (std::size_t i = 0; i < nodes; ++i)
    surface.top = std::max(surface.top, result.positions[3 * i + 2]);
  for (std::size_t i = 0; i < nodes; ++i) {
    if (result.positions[3 * i + 2] >= surface.top - result.scene.spacing / 2) {
      surface.nodes.push_back(i);
      surface.mean_y += result.positions[3 * i + 1];
    }
  }
  if (!surface.nodes.empty()) surface.mean_y /= static_cast<double>(surface.nodes.size());
  return surface;
}

// The pair's traces at the surface and their meeting depth. Both traces descend inwards, so
// they meet below the surface at depth d where their horizontal gap closes:
// gap = d (cot dip_left + cot dip_right) in the x-z section.
Graben pair_geometry(const std::vector<Fault>& faults, std::size_t l, std::size_t r,
                     const Surface& surface) {
  const Fault& left = faults[l];
  const Fault& right = faults[r];
  Graben graben;
  graben.left_fault = l;
  graben.right_fault = r;
  graben.left_surface_x = trace_x(left, surface.mean_y, surface.top);
  graben.right_surface_x = trace_x(right, surface.mean_y, surface.top);
  const double closing =
      left.normal[2] / std::abs(left.normal[0]) + right.normal[2] / std::abs(right.normal[0]);
  graben.apex_depth = (graben.right_surface_x - graben.left_surface_x) / closing;
  return graben;
}

// Whether the fault's centroid lies in the block: between the two traces, above their apex.
bool inside_block(const Fault& fault, const std::vector<Fault>& faults, const Graben& graben,
                  double top) {
  const auto& c = fault.centroid;
  return c[2] > top - graben.apex_depth && c[0] > trace_x(faults[graben.left_fault], c[1], c[2]) &&
         c[0] < trace_x(faults[graben.right_fault], c[1], c[2]);
}

double subsidence(const RunResult& result, const Snapshot& snapshot, const Surface& surface,
                  const Fault& left, const Fault& right) {
  const double spacing = result.scene.spacing;
  double inside_sum = 0, outside_sum = 0;
  std::int64_t inside = 0, outside = 0;
  for (const std::size_t i : surface.nodes) {
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
  return inside > 0 && outside > 0 ? outside_sum / outside - inside_sum / inside
                                   : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::vector<Graben> find_grabens(const RunResult& result, const Snapshot& snapshot,
                                 const std::vector<Fault>& faults, const FaultOptions& options) {
  const Surface surface = surface_of(result);
  if (surface.nodes.empty()) return {};
  std::vector<std::size_t> lefts, rights;
  for (std::size_t f = 0; f < faults.size(); ++f) {
    if (!bounds_graben(faults[f], options)) continue;
    (faults[f].dip_direction == 1 ? lefts : rights).push_back(f);
  }

  // 1. Every pair whose traces meet below the surface with both faults above that point. Two
  // faults below it, such as the arms of an inverted V, dip away from each other where they
  // exist: no graben.
  std::vector<Graben> pairs;
  std::set<std::pair<std::size_t, std::size_t>> paired;
  for (const std::size_t l : lefts) {
    for (const std::size_t r : rights) {
      const Graben graben = pair_geometry(faults, l, r, surface);
      if (!(graben.left_surface_x < graben.right_surface_x)) continue;
      const double apex_z = surface.top - graben.apex_depth;
      if (!(faults[l].centroid[2] > apex_z && faults[r].centroid[2] > apex_z)) continue;
      pairs.push_back(graben);
      paired.insert({l, r});
    }
  }

  // 2. The innermost: a pair whose block holds another pair (each of its faults one of this
  // pair's or inside the block) is not a graben.
  std::vector<Graben> grabens;
  for (Graben& graben : pairs) {
    std::vector<std::size_t> inner_lefts{graben.left_fault}, inner_rights{graben.right_fault};
    for (const std::size_t l : lefts)
      if (l != graben.left_fault && inside_block(faults[l], faults, graben, surface.top))
        inner_lefts.push_back(l);
    for (const std::size_t r : rights)
      if (r != graben.right_fault && inside_block(faults[r], faults, graben, surface.top))
        inner_rights.push_back(r);
    bool holds_another = false;
    for (const std::size_t l : inner_lefts)
      for (const std::size_t r : inner_rights)
        holds_another |=
            (l != graben.left_fault || r != graben.right_fault) && paired.count({l, r});
    if (holds_another) continue;
    graben.surface_subsidence = subsidence(result, snapshot, surface, faults[graben.left_fault],
                                           faults[graben.right_fault]);
    grabens.push_back(graben);
  }
  std::sort(grabens.begin(), grabens.end(), [](const Graben& a, const Graben& b) {
    return std::tie(a.left_surface_x, a.right_surface_x, a.left_fault, a.right_fault) <
           std::tie(b.left_surface_x, b.right_surface_x, b.left_fault, b.right_fault);
  });
  return grabens;
}

}  // namespace latfrac
