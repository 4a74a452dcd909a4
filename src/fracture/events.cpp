// Closed-form events on affine paths: bond crossings and contact switches.
#include "latfrac/fracture/events.h"

#include <cmath>

#include "latfrac/criteria/crossing.h"
#include "latfrac/mechanics/node_stress.h"

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
  const CriterionParameters& criterion = evaluator.parameters();
  const bool drucker_prager = criterion.criterion == Criterion::drucker_prager;
  std::vector<double> stress0, stress1;
  if (evaluator.uses_tensor()) {
    stress0 = node_stresses(model, full.at_zero);
    stress1 = node_stresses(model, full.at_zero + full.per_lambda);
    for (std::size_t k = 0; k < stress1.size(); ++k) stress1[k] -= stress0[k];
  }
  std::vector<double> crossing(model.lattice.bond_count(), std::numeric_limits<double>::infinity());
  double first = std::numeric_limits<double>::infinity();
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (!model.intact[b]) continue;
    double s;
    if (drucker_prager) {
      const Bond& bond = model.lattice.bonds[b];
      VoigtStress s0 = bond_stress_tensor(stress0, bond), s1 = bond_stress_tensor(stress1, bond);
      for (double& value : s1) value *= sign;
      s = first_crossing_drucker_prager(s0, s1, criterion.dp_alpha,
                                        criterion.dp_k_per_cohesion * model.bond_tau0[b], s_from,
                                        s_to);
    } else if (evaluator.bond_stress() == BondStress::critical_plane) {
      // f is convex in lambda but not a polynomial: bisection, only up to the earliest
      // crossing found so far (a later one cannot come first), with room for ties.
      const Bond& bond = model.lattice.bonds[b];
      const VoigtStress s0 = bond_stress_tensor(stress0, bond);
      VoigtStress s1 = bond_stress_tensor(stress1, bond);
      for (double& value : s1) value *= sign;
      const auto f = [&](double l) {
        VoigtStress at;
        for (int k = 0; k < 6; ++k) at[k] = s0[k] + l * s1[k];
        return critical_plane_index(criterion.criterion, at, model.dim(), model.bond_sigma0[b],
                                    model.bond_tau0[b])
            .value;
      };
      const double until =
          std::isfinite(first)
              ? std::min(s_to, first + 2 * FailureEvaluator::tie_tolerance *
                                           std::max(std::abs(first), 1e-300))
              : s_to;
      s = first_crossing_convex(f, s_from, until);
    } else if (evaluator.uses_tensor()) {
      // The resolved stresses are linear in the tensor, so affine in lambda with it.
      const Bond& bond = model.lattice.bonds[b];
      const Vec3& n0 = model.lattice.bond_direction[b];
      VoigtStress s1 = bond_stress_tensor(stress1, bond);
      for (double& value : s1) value *= sign;
      const ResolvedStress r0 = resolve_on(bond_stress_tensor(stress0, bond), n0);
      const ResolvedStress r1 = resolve_on(s1, n0);
      const AffineBondStress affine{r0.normal, r1.normal, r0.shear, r1.shear};
      s = first_crossing(criterion.criterion, affine, model.bond_sigma0[b], model.bond_tau0[b],
                         s_from, s_to);
    } else {
      const Vec3& n0 = model.lattice.bond_direction[b];
      const double length = model.lattice.bond_length[b];
      const Vec3 du0 = model.bond_displacement(full.at_zero, b);
      const Vec3 du1 = sign * model.bond_displacement(full.per_lambda, b);
      const double e = model.bond_young[b] / length, g = model.bond_shear_modulus[b] / length;
      AffineBondStress affine;
      affine.normal0 = e * n0.dot(du0);
      affine.normal1 = e * n0.dot(du1);
      affine.shear0 = g * (du0 - n0.dot(du0) * n0);
      affine.shear1 = g * (du1 - n0.dot(du1) * n0);
      s = first_crossing(criterion.criterion, affine, model.bond_sigma0[b], model.bond_tau0[b],
                         s_from, s_to);
    }
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
