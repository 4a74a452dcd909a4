// Failure indices of the bonds of a model, and their crossings along affine paths.
#include "latfrac/criteria/failure_evaluator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "latfrac/base/phase_times.h"
#include "latfrac/base/threads.h"
#include "latfrac/mechanics/node_stress.h"

namespace latfrac {

FailureEvaluator::FailureEvaluator(std::shared_ptr<const FailureCriterion> criterion,
                                   BondStress reading, const Model& model)
    : criterion_(std::move(criterion)), bond_stress_(reading) {
  reading_ = criterion_->tensor_only() || reading == BondStress::critical_plane
                 ? Reading::tensor_index
             : reading == BondStress::tensor ? Reading::resolved_tensor
                                             : Reading::strain;
  uses_tensor_ = reading_ != Reading::strain;
  const std::int64_t bonds = model.lattice.bond_count();
  normal_scale_.resize(bonds);
  shear_scale_.resize(bonds);
  for (std::int64_t b = 0; b < bonds; ++b) {
    const double length = model.lattice.bond_length[b];
    normal_scale_[b] = model.bond_young[b] / (length * model.bond_sigma0[b]);
    shear_scale_[b] = model.bond_shear_modulus[b] / (length * model.bond_tau0[b]);
  }
}

FailureEvaluator::FailureEvaluator(const Strength& strength, const Model& model)
    : FailureEvaluator(make_criterion(strength, model.dim()), strength.bond_stress, model) {}

VoigtStress bond_stress_tensor(const std::vector<double>& node_stress, const Bond& bond) {
  VoigtStress s{};
  for (int k = 0; k < 6; ++k)
    s[k] = 0.5 * (node_stress[6 * bond.i + k] + node_stress[6 * bond.j + k]);
  return s;
}

FailureIndex FailureEvaluator::bond_index(const Model& model, const Vector& displacement,
                                          std::int64_t bond,
                                          const std::vector<double>& node_stress) const {
  const BondStrength strength = strength_of(model, bond);
  if (reading_ != Reading::strain) {
    const VoigtStress stress = bond_stress_tensor(node_stress, model.lattice.bonds[bond]);
    if (reading_ == Reading::tensor_index) return criterion_->tensor_index(stress, strength);
    const ResolvedStress r = resolve_on(stress, model.lattice.bond_direction[bond]);
    return criterion_->index(r.normal, r.shear.norm(), strength);
  }
  // The bond law's own normal and shear displacement (the current direction under large
  // kinematics).
  const double length = model.lattice.bond_length[bond];
  const BondDeformation d = model.bond_law().deformation({model.lattice.bond_direction[bond], length},
                                                   model.bond_displacement(displacement, bond));
  return criterion_->index(model.bond_young[bond] * d.normal / length,
                           model.bond_shear_modulus[bond] * d.shear.norm() / length, strength);
}

void FailureEvaluator::evaluate(const Model& model, const Vector& displacement,
                                std::vector<double>& index, std::vector<BreakMode>& mode) const {
  const ScopedPhase phase(Phase::criterion);
  const std::int64_t bonds = model.lattice.bond_count();
  index.assign(bonds, 0.0);
  mode.assign(bonds, BreakMode::tensile);
  std::vector<double> node_stress;
  if (uses_tensor_) node_stress = node_stresses(model, displacement);
  for (std::int64_t b = 0; b < bonds; ++b) {
    if (!model.intact(b)) continue;
    const FailureIndex f = bond_index(model, displacement, b, node_stress);
    index[b] = f.value;
    mode[b] = f.mode;
  }
}

std::vector<CriticalBond> FailureEvaluator::indices_of(const Model& model, const Vector& displacement,
                                                       const std::vector<std::int64_t>& bonds) const {
  const ScopedPhase phase(Phase::criterion);
  std::vector<double> node_stress;
  if (uses_tensor_) {
    // Only the listed bonds' ends are read.
    std::vector<std::int64_t> ends;
    for (const std::int64_t b : bonds)
      ends.insert(ends.end(), {model.lattice.bonds[b].i, model.lattice.bonds[b].j});
    std::sort(ends.begin(), ends.end());
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
    node_stress = node_stresses_at(model, displacement, ends);
  }
  std::vector<CriticalBond> out;
  out.reserve(bonds.size());
  for (std::int64_t b : bonds) {
    const FailureIndex f = bond_index(model, displacement, b, node_stress);
    out.push_back({b, f.value, f.mode});
  }
  return out;
}

// The hot loop of every cascade: on the strain reading with a linear law the criterion
// ranks from the normal ratio and the squared shear ratio, free of square roots.
double FailureEvaluator::rank(const Model& model, const Vector& displacement, std::int64_t b,
                              const std::vector<double>& node_stress) const {
  if (uses_tensor_ || !model.is_linear()) {
    return bond_index(model, displacement, b, node_stress).value;
  }
  const Vec3& n0 = model.lattice.bond_direction[b];
  const Vec3 du = model.bond_displacement(displacement, b);
  const double dn = n0.dot(du);
  const double normal = std::max(dn, 0.0) * normal_scale_[b];
  double shear_squared =
      std::max(du.squaredNorm() - dn * dn, 0.0) * shear_scale_[b] * shear_scale_[b];
  // With internal friction the shear strength is tau0 (1 + mu <-sigma_n>+ / tau0).
  const double mu = parameters().internal_friction;
  if (mu > 0) {
    const double compression = std::max(-dn, 0.0) * normal_scale_[b] * model.bond_sigma0[b];
    const double gain = 1 + mu * compression / model.bond_tau0[b];
    shear_squared /= gain * gain;
  }
  return criterion_->rank(normal, shear_squared);
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
  const ScopedPhase phase(Phase::criterion);
  std::vector<double> node_stress;
  if (uses_tensor_) node_stress = node_stresses(model, displacement);
  const double tolerance = rank_tolerance();
  // Every intact bond's rank, on threads (each bond on its own); 0 for the others.
  const std::int64_t bonds = model.lattice.bond_count();
  std::vector<double> ranks(bonds, 0.0);
  threads::for_blocks(bonds, threads::bond_grain, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t b = first; b < last; ++b)
      if (model.intact(b)) ranks[b] = rank(model, displacement, b, node_stress);
  });
  double best = 0;
  for (const double r : ranks) best = std::max(best, r);
  std::vector<CriticalBond> group;
  for (std::int64_t b = 0; b < bonds; ++b) {
    if (ranks[b] <= 0 || ranks[b] < best * (1 - tolerance)) continue;
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

PathStresses FailureEvaluator::path_stresses(const Model& model, const Vector& at_zero,
                                             const Vector& per_lambda, double sign) const {
  PathStresses path{at_zero, sign * per_lambda, {}, {}};
  if (uses_tensor_) {
    // On an affine path the law is linear, and so is the virial in the displacement.
    NodeStressPath stresses = node_stress_path(model, at_zero, path.per_unit);
    path.stress_at_zero = std::move(stresses.at_zero);
    path.stress_per_unit = std::move(stresses.per_unit);
  }
  return path;
}

namespace {

// Whether f can reach 1 on [from, until] when index() grows with sigma_n and tau: it is
// at most index(the larger sigma_n at the ends, the larger |tau| at the ends). The margin
// keeps a bond whose f at `from` rounds differently here than in the crossing search.
// With `error`, the same for any stresses within that distance of s's (Pa).
bool may_reach_one(const FailureCriterion& criterion, const AffineBondStress& s,
                   const BondStrength& strength, double from, double until, double error = 0) {
  if (!criterion.index_grows_with_stress() || !std::isfinite(until)) return true;
  const double normal = std::max(s.normal0 + from * s.normal1, s.normal0 + until * s.normal1);
  const double shear =
      std::max((s.shear0 + from * s.shear1).norm(), (s.shear0 + until * s.shear1).norm());
  return criterion.index(normal + error, shear + error, strength).value >= 1 - 1e-9;
}

}  // namespace

bool FailureEvaluator::may_fail_at(const Model& model, const PathStresses& path, double s) const {
  const ScopedPhase phase(Phase::criterion);
  // On the strain reading the exact check needs no node stresses: nothing to save.
  if (!uses_tensor_) return true;
  // The node stresses at s, then each bond's f from them as the exact check computes it.
  std::vector<double> node_stress(path.stress_at_zero.size());
  for (std::size_t k = 0; k < node_stress.size(); ++k)
    node_stress[k] = path.stress_at_zero[k] + s * path.stress_per_unit[k];
  const Vector none;
  std::atomic<bool> found = false;
  threads::for_blocks(model.lattice.bond_count(), threads::bond_grain, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t b = first; b < last && !found.load(std::memory_order_relaxed); ++b) {
      if (!model.intact(b)) continue;
      // NaN passes too: the exact check decides.
      if (!(bond_index(model, none, b, node_stress).value < 1 - screen_margin)) found = true;
    }
  });
  return found;
}

bool FailureEvaluator::may_cross_near(const Model& model, std::int64_t b,
                                      const AffineBondStress& near, double error, double from,
                                      double until) const {
  return may_reach_one(*criterion_, near, strength_of(model, b), from, until, error);
}

AffineBondStress FailureEvaluator::affine_stress(const Model& model, std::int64_t b,
                                                 const PathStresses& path) const {
  const Vec3& n0 = model.lattice.bond_direction[b];
  if (reading_ == Reading::resolved_tensor) {
    const Bond& bond = model.lattice.bonds[b];
    const ResolvedStress r0 = resolve_on(bond_stress_tensor(path.stress_at_zero, bond), n0);
    const ResolvedStress r1 = resolve_on(bond_stress_tensor(path.stress_per_unit, bond), n0);
    return {r0.normal, r1.normal, r0.shear, r1.shear};
  }
  const double length = model.lattice.bond_length[b];
  const Vec3 du0 = model.bond_displacement(path.at_zero, b);
  const Vec3 du1 = model.relative_motion(path.per_unit, b);
  const double e = model.bond_young[b] / length, g = model.bond_shear_modulus[b] / length;
  AffineBondStress affine;
  affine.normal0 = e * n0.dot(du0);
  affine.normal1 = e * n0.dot(du1);
  affine.shear0 = g * (du0 - n0.dot(du0) * n0);
  affine.shear1 = g * (du1 - n0.dot(du1) * n0);
  return affine;
}

// Along the path every bond quantity is affine in s: the stress tensor, its resolution on
// the bond direction (linear in the tensor), and the strains. A bond whose f cannot reach
// 1 before `needed_until` (nor before `to`) is skipped: its crossing, if any, is later.
double FailureEvaluator::first_crossing(const Model& model, std::int64_t b,
                                        const PathStresses& path, double from, double to,
                                        double needed_until) const {
  const BondStrength strength = strength_of(model, b);
  const double until = std::min(to, needed_until);
  if (reading_ == Reading::tensor_index) {
    const Bond& bond = model.lattice.bonds[b];
    return criterion_->first_tensor_crossing(bond_stress_tensor(path.stress_at_zero, bond),
                                             bond_stress_tensor(path.stress_per_unit, bond),
                                             strength, from, to, needed_until);
  }
  const AffineBondStress affine = affine_stress(model, b, path);
  if (!may_reach_one(*criterion_, affine, strength, from, until))
    return std::numeric_limits<double>::infinity();
  return criterion_->first_crossing(affine, strength, from, to);
}

}  // namespace latfrac
