// Ruling bonds out of a crossing search by bounds (path_screen.h).
#include "latfrac/fracture/path_screen.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "latfrac/base/parallel.h"
#include "latfrac/base/phase_times.h"
#include "latfrac/base/threads.h"
#include "latfrac/fracture/break_source.h"
#include "latfrac/mechanics/bond_law.h"
#include "latfrac/mechanics/node_stress.h"

namespace latfrac {

namespace {

// The largest |a + s b| over the entries: a bound, up to rounding, of a full
// displacement's largest entry.
double largest(const Vector& a, const Vector* b = nullptr, double s = 0) {
  double most = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k)
    most = std::max(most, std::abs(b ? a[k] + s * (*b)[k] : a[k]));
  return most;
}

}  // namespace

bool PathScreen::applies(const Model& model, const FailureEvaluator& evaluator) {
  return evaluator.bounds_rule_out() && !parallel::distributed() &&
         dynamic_cast<const SmallKinematics*>(&model.bond_law()) != nullptr;
}

PathScreen::PathScreen(const Model& model, const FailureEvaluator& evaluator)
    : model_(model), evaluator_(evaluator) {
  const std::vector<double> node_bound = node_stress_bounds(model);
  const Lattice& lattice = model.lattice;
  bond_bound_.resize(lattice.bond_count());
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b)
    bond_bound_[b] = 0.5 * (node_bound[lattice.bonds[b].i] + node_bound[lattice.bonds[b].j]);
}

void PathScreen::set_reference(const FullPath& full, const PathStresses& stresses, double sign,
                               std::int64_t breaks) {
  const ScopedPhase phase(Phase::criterion);
  const std::int64_t bonds = model_.lattice.bond_count();
  stress_.resize(bonds);
  threads::for_blocks(bonds, threads::bond_grain, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t b = first; b < last; ++b)
      if (model_.intact(b)) stress_[b] = evaluator_.affine_stress(model_, b, stresses);
  });
  at_zero_ = full.at_zero;
  per_lambda_ = full.per_lambda;
  free_index_ = model_.dofs().free_index;
  sign_ = sign;
  breaks_ = breaks;
  valid_ = true;
  ++full_;
}

std::optional<PathCrossing> PathScreen::next_break(const FullPath& full, double from, double to,
                                                   double needed_until, std::int64_t breaks) {
  const double sign = to < from ? -1.0 : 1.0;
  if (!valid_ || sign != sign_ || breaks != breaks_ || model_.dofs().free_index != free_index_)
    return std::nullopt;
  const ScopedPhase phase(Phase::criterion);
  // The interval to rule out, in s = sign lambda: up to the search's need, with more room
  // than its tie window.
  const double s_from = sign * from, s_to = sign * to;
  double until = s_to;
  if (!std::isnan(needed_until)) {
    const double s_needed = sign * needed_until;
    until = std::min(until, s_needed + 4 * FailureEvaluator::tie_tolerance *
                                           std::max(std::abs(s_needed), 1e-300));
  }
  // How far the displacement can be from the reference's over [s_from, until], with a
  // relative allowance for the rounding of these sums.
  const Vector moved = full.at_zero - at_zero_, turned = sign * (full.per_lambda - per_lambda_);
  const double distance =
      (largest(moved, &turned, s_from) + std::max(until - s_from, 0.0) * largest(turned)) *
      (1 + 1e-6);
  if (!std::isfinite(distance)) return std::nullopt;
  const std::int64_t bonds = model_.lattice.bond_count();
  std::vector<std::uint8_t> left(bonds, 0);
  threads::for_blocks(bonds, threads::bond_grain, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t b = first; b < last; ++b)
      if (model_.intact(b))
        left[b] = evaluator_.may_cross_near(model_, b, stress_[b], bond_bound_[b] * distance,
                                            s_from, until)
                      ? 2
                      : 1;
  });
  std::int64_t intact = 0;
  std::vector<std::int64_t> searched;
  for (std::int64_t b = 0; b < bonds; ++b) {
    if (left[b] == 0) continue;
    ++intact;
    if (left[b] == 2) searched.push_back(b);
  }
  if (static_cast<double>(searched.size()) > most_left * static_cast<double>(intact))
    return std::nullopt;
  ++screened_;
  if (searched.empty()) return PathCrossing{};
  std::vector<std::int64_t> nodes;
  nodes.reserve(2 * searched.size());
  for (const std::int64_t b : searched) {
    nodes.push_back(model_.lattice.bonds[b].i);
    nodes.push_back(model_.lattice.bonds[b].j);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  const Vector per_unit = sign * full.per_lambda;
  NodeStressPath at_nodes = node_stress_path_at(model_, full.at_zero, per_unit, nodes);
  PathStresses stresses;
  stresses.stress_at_zero = std::move(at_nodes.at_zero);
  stresses.stress_per_unit = std::move(at_nodes.per_unit);
  return next_break_among(model_, evaluator_, stresses, searched, from, to, needed_until);
}

}  // namespace latfrac
