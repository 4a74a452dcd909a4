// Failure indices of the bonds of a model.
#include "latfrac/fracture.h"

#include "latfrac/node_stress.h"

namespace latfrac {

FailureEvaluator::FailureEvaluator(const Strength& strength, const Model& model)
    : parameters_(resolve_criterion(strength, model.dim())) {
  const std::int64_t bonds = model.lattice.bond_count();
  normal_scale_.resize(bonds);
  shear_scale_.resize(bonds);
  for (std::int64_t b = 0; b < bonds; ++b) {
    const double length = model.lattice.bond_length[b];
    normal_scale_[b] = model.bond_young[b] / (length * model.bond_sigma0[b]);
    shear_scale_[b] = model.bond_shear_modulus[b] / (length * model.bond_tau0[b]);
  }
}

FailureIndex FailureEvaluator::bond_index(const Model& model, const Vector& displacement,
                                          std::int64_t bond, const std::vector<double>& node_stress) const {
  if (parameters_.criterion == Criterion::drucker_prager) {
    const Bond& pair = model.lattice.bonds[bond];
    std::array<double, 6> stress{};
    for (int k = 0; k < 6; ++k) stress[k] = 0.5 * (node_stress[6 * pair.i + k] + node_stress[6 * pair.j + k]);
    return drucker_prager_index(stress, parameters_.dp_alpha,
                                parameters_.dp_k_per_cohesion * model.bond_tau0[bond]);
  }
  const Vec3& n0 = model.lattice.bond_direction[bond];
  const Vec3 du = model.bond_displacement(displacement, bond);
  const double dn = n0.dot(du);
  const double shear = (du - dn * n0).norm();
  const double length = model.lattice.bond_length[bond];
  return failure_index(parameters_.criterion, model.bond_young[bond] * dn / length,
                       model.bond_shear_modulus[bond] * shear / length, model.bond_sigma0[bond],
                       model.bond_tau0[bond]);
}

void FailureEvaluator::evaluate(const Model& model, const Vector& displacement, std::vector<double>& index,
                                std::vector<BreakMode>& mode) const {
  const std::int64_t bonds = model.lattice.bond_count();
  index.assign(bonds, 0.0);
  mode.assign(bonds, BreakMode::tensile);
  std::vector<double> node_stress;
  if (parameters_.criterion == Criterion::drucker_prager) node_stress = node_stresses(model, displacement);
  for (std::int64_t b = 0; b < bonds; ++b) {
    if (!model.intact[b]) continue;
    const FailureIndex f = bond_index(model, displacement, b, node_stress);
    index[b] = f.value;
    mode[b] = f.mode;
  }
}

// The hot loop of every cascade. For the stress-based criteria it ranks bonds by a
// quantity monotone in f that needs no square root (the normal ratio, the larger of the
// squared ratios, or f itself for the ellipse), then computes the winner's f exactly.
CriticalBond FailureEvaluator::most_critical(const Model& model, const Vector& displacement) const {
  std::vector<double> node_stress;
  const Criterion criterion = parameters_.criterion;
  if (criterion == Criterion::drucker_prager) node_stress = node_stresses(model, displacement);
  std::int64_t best = -1;
  double best_rank = 0;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (!model.intact[b]) continue;
    double rank;
    if (criterion == Criterion::drucker_prager) {
      rank = bond_index(model, displacement, b, node_stress).value;
    } else {
      const Vec3& n0 = model.lattice.bond_direction[b];
      const Vec3 du = model.bond_displacement(displacement, b);
      const double dn = n0.dot(du);
      const double normal = std::max(dn, 0.0) * normal_scale_[b];
      const double shear_squared = std::max(du.squaredNorm() - dn * dn, 0.0) * shear_scale_[b] * shear_scale_[b];
      rank = criterion == Criterion::tensile           ? normal
             : criterion == Criterion::elliptic        ? normal * normal + shear_squared
                                                       : std::max(normal * normal, shear_squared);
    }
    if (best < 0 || rank > best_rank) {
      best = b;
      best_rank = rank;
    }
  }
  if (best < 0) return {};
  const FailureIndex f = bond_index(model, displacement, best, node_stress);
  return {best, f.value, f.mode};
}

}  // namespace latfrac
