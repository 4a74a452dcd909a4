// Failure indices of the bonds of a model.
#include "latfrac/criteria/failure_evaluator.h"

#include <algorithm>

#include "latfrac/mechanics/node_stress.h"

namespace latfrac {

FailureEvaluator::FailureEvaluator(const Strength& strength, const Model& model)
    : parameters_(resolve_criterion(strength, model.dim())),
      bond_stress_(strength.bond_stress),
      uses_tensor_(parameters_.criterion == Criterion::drucker_prager ||
                   strength.bond_stress != BondStress::strain) {
  const std::int64_t bonds = model.lattice.bond_count();
  normal_scale_.resize(bonds);
  shear_scale_.resize(bonds);
  for (std::int64_t b = 0; b < bonds; ++b) {
    const double length = model.lattice.bond_length[b];
    normal_scale_[b] = model.bond_young[b] / (length * model.bond_sigma0[b]);
    shear_scale_[b] = model.bond_shear_modulus[b] / (length * model.bond_tau0[b]);
  }
}

VoigtStress bond_stress_tensor(const std::vector<double>& node_stress, const Bond& bond) {
  VoigtStress s{};
  for (int k = 0; k < 6; ++k)
    s[k] = 0.5 * (node_stress[6 * bond.i + k] + node_stress[6 * bond.j + k]);
  return s;
}

FailureIndex FailureEvaluator::bond_index(const Model& model, const Vector& displacement,
                                          std::int64_t bond,
                                          const std::vector<double>& node_stress) const {
  if (uses_tensor_) {
    const VoigtStress stress = bond_stress_tensor(node_stress, model.lattice.bonds[bond]);
    if (parameters_.criterion == Criterion::drucker_prager)
      return drucker_prager_index(stress, parameters_.dp_alpha,
                                  parameters_.dp_k_per_cohesion * model.bond_tau0[bond]);
    if (bond_stress_ == BondStress::critical_plane)
      return critical_plane_index(parameters_.criterion, stress, model.dim(),
                                  model.bond_sigma0[bond], model.bond_tau0[bond]);
    const ResolvedStress r = resolve_on(stress, model.lattice.bond_direction[bond]);
    return failure_index(parameters_.criterion, r.normal, r.shear.norm(),
                         model.bond_sigma0[bond], model.bond_tau0[bond]);
  }
  // The bond law's own normal and shear displacement (the current direction under large
  // kinematics).
  const double length = model.lattice.bond_length[bond];
  const BondDeformation d = model.law->deformation({model.lattice.bond_direction[bond], length},
                                                   model.bond_displacement(displacement, bond));
  const double dn = d.normal, shear = d.shear.norm();
  return failure_index(parameters_.criterion, model.bond_young[bond] * dn / length,
                       model.bond_shear_modulus[bond] * shear / length, model.bond_sigma0[bond],
                       model.bond_tau0[bond]);
}

void FailureEvaluator::evaluate(const Model& model, const Vector& displacement,
                                std::vector<double>& index, std::vector<BreakMode>& mode) const {
  const std::int64_t bonds = model.lattice.bond_count();
  index.assign(bonds, 0.0);
  mode.assign(bonds, BreakMode::tensile);
  std::vector<double> node_stress;
  if (uses_tensor_) node_stress = node_stresses(model, displacement);
  for (std::int64_t b = 0; b < bonds; ++b) {
    if (!model.intact[b]) continue;
    const FailureIndex f = bond_index(model, displacement, b, node_stress);
    index[b] = f.value;
    mode[b] = f.mode;
  }
}

// The hot loop of every cascade. For the stress-based criteria the ranking quantity is
// the normal ratio (tensile), f itself (elliptic) or the larger squared ratio
// (tensile_or_shear): monotone in f, and free of square roots.
double FailureEvaluator::rank(const Model& model, const Vector& displacement, std::int64_t b,
                              const std::vector<double>& node_stress) const {
  const Criterion criterion = parameters_.criterion;
  if (uses_tensor_ || !model.law->is_linear()) {
    return bond_index(model, displacement, b, node_stress).value;
  }
  const Vec3& n0 = model.lattice.bond_direction[b];
  const Vec3 du = model.bond_displacement(displacement, b);
  const double dn = n0.dot(du);
  const double normal = std::max(dn, 0.0) * normal_scale_[b];
  const double shear_squared =
      std::max(du.squaredNorm() - dn * dn, 0.0) * shear_scale_[b] * shear_scale_[b];
  return criterion == Criterion::tensile    ? normal
         : criterion == Criterion::elliptic ? normal * normal + shear_squared
                                            : std::max(normal * normal, shear_squared);
}

double FailureEvaluator::rank_tolerance() const {
  // The squared ratio of tensile_or_shear doubles the relative spread; a margin of two
  // more keeps every tied bond among the candidates (the exact f decides). The exact f
  // is the rank itself on the stress tensor and for a nonlinear law.
  return 4 * tie_tolerance;
}

CriticalBond FailureEvaluator::most_critical(const Model& model, const Vector& displacement) const {
  const std::vector<CriticalBond> group = critical_group(model, displacement, 0.0);
  return group.empty() ? CriticalBond{} : group.front();
}

std::vector<CriticalBond> FailureEvaluator::critical_group(const Model& model,
                                                           const Vector& displacement,
                                                           double threshold) const {
  std::vector<double> node_stress;
  if (uses_tensor_) node_stress = node_stresses(model, displacement);
  const double tolerance = rank_tolerance();
  double best = 0;
  std::vector<std::int64_t> candidates;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (!model.intact[b]) continue;
    const double r = rank(model, displacement, b, node_stress);
    if (r <= 0 || r < best * (1 - tolerance)) continue;
    candidates.push_back(b);
    best = std::max(best, r);
  }
  std::vector<CriticalBond> group;
  for (std::int64_t b : candidates) {
    if (rank(model, displacement, b, node_stress) < best * (1 - tolerance)) continue;
    const FailureIndex f = bond_index(model, displacement, b, node_stress);
    group.push_back({b, f.value, f.mode});
  }
  if (group.empty()) return group;
  const double largest = std::max_element(group.begin(), group.end(), [](auto& p, auto& q) {
                           return p.index < q.index;
                         })->index;
  std::erase_if(group,
                [&](const CriticalBond& c) { return c.index < largest * (1 - tie_tolerance); });
  // Their failure indices are equal within the tolerance: the order is the bond id, so
  // that rounding cannot reorder a group from one build to the next.
  std::sort(group.begin(), group.end(),
            [](const CriticalBond& p, const CriticalBond& q) { return p.bond < q.bond; });
  if (largest < threshold) group.clear();
  return group;
}

}  // namespace latfrac
