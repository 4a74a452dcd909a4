// Closed-form events on affine paths: bond crossings and contact switches.
#include "latfrac/fracture/events.h"

#include <cmath>


namespace latfrac {
namespace {

// The path's full displacement at lambda = 0 and per unit lambda.
struct FullPath {
  Vector at_zero, per_lambda;
};

FullPath full_path(const Model& model, const AffinePath& path) {
  FullPath full;
  full.at_zero = model.full_displacement(path.gravity, 0.0);
  full.per_lambda = model.full_displacement(path.at(1.0), 1.0) - full.at_zero;
  return full;
}

}  // namespace

PathCrossing next_break(const Model& model, const FailureEvaluator& evaluator,
                        const AffinePath& path, double from, double to) {
  const double sign = to < from ? -1.0 : 1.0;  // search in s = sign * lambda, increasing
  const double s_from = sign * from, s_to = sign * to;
  const FullPath full = full_path(model, path);
  const PathStresses stresses = evaluator.path_stresses(model, full.at_zero, full.per_lambda, sign);
  std::vector<double> crossing(model.lattice.bond_count(), std::numeric_limits<double>::infinity());
  double first = std::numeric_limits<double>::infinity();
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (!model.intact[b]) continue;
    // Only a crossing up to the earliest found so far (with room for ties) can matter.
    const double needed_until =
        std::isfinite(first)
            ? first + 2 * FailureEvaluator::tie_tolerance * std::max(std::abs(first), 1e-300)
            : std::numeric_limits<double>::infinity();
    const double s = evaluator.first_crossing(model, b, stresses, s_from, s_to, needed_until);
    crossing[b] = s;
    first = std::min(first, s);
  }
  if (!std::isfinite(first)) return {};
  // Ties within rounding: the largest f at the crossing, then the lowest id.
  const double lambda = sign * first;
  const double window = first + FailureEvaluator::tie_tolerance * std::max(std::abs(first), 1e-300);
  const Vector u = full.at_zero + lambda * full.per_lambda;
  std::vector<double> index;
  std::vector<BreakMode> modes;
  PathCrossing event;
  double best = -1;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (crossing[b] > window) continue;
    if (index.empty()) evaluator.evaluate(model, u, index, modes);
    event.tied.push_back(b);
    if (index[b] > best) {
      best = index[b];
      event.bond = b;
    }
  }
  event.lambda = lambda;
  return event;
}

PathCrossing next_contact_switch(const Model& model, const AffinePath& path, double from,
                                 double to, bool at_from) {
  const double sign = to < from ? -1.0 : 1.0;
  const double s_from = sign * from, s_to = sign * to;
  const FullPath full = full_path(model, path);
  PathCrossing event;
  double first = std::numeric_limits<double>::infinity();
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (!model.contact_capable(b)) continue;
    const Vec3& n0 = model.lattice.bond_direction[b];
    const double dn0 = n0.dot(model.bond_displacement(full.at_zero, b));
    const double rate = sign * n0.dot(model.bond_displacement(full.per_lambda, b));
    const bool active = model.contact_active[b];
    // dn(s) = dn0 + rate s: an active contact opens when it rises through 0, an open one
    // closes when it falls through 0.
    if (rate == 0 || (active && rate < 0) || (!active && rate > 0)) continue;
    const bool past = active ? dn0 + rate * s_from >= 0 : dn0 + rate * s_from <= 0;
    // At `from` a rate that rounding could have given either sign decides nothing: such a
    // contact moves less than 1e-12 a (the switching tolerance) per 1e-3 of lambda, 4e-11 a
    // over the paper's whole loading to 0.04.
    if (past && (!at_from || std::abs(rate) <= 1e-9 * model.lattice.spacing)) continue;
    const double s = past ? s_from : -dn0 / rate;
    if ((past || s > s_from) && s <= s_to && s < first) {
      first = s;
      event.bond = b;
    }
  }
  if (event.found()) event.lambda = sign * first;
  return event;
}

}  // namespace latfrac
