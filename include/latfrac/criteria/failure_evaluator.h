// Failure indices of every intact bond: which bond breaks next, how, and when on a path.
//
// A bond's normal and shear stresses come from its strains and its layer's moduli,
// sigma_n = E dn / L0 and tau = G |ds| / L0 (model.md section 2), or, with
// bond_stress = "tensor", from the bond's stress tensor resolved on its direction, or,
// with bond_stress = "critical_plane", from that tensor on the plane where f is largest.
// A criterion that only a tensor defines (Drucker-Prager) always uses the tensor, the
// mean of the two nodes' virial stresses. The criteria themselves are in criterion.h;
// this class is the one place that chooses the reading.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "latfrac/criteria/criterion.h"
#include "latfrac/mechanics/model.h"

namespace latfrac {

struct CriticalBond {
  std::int64_t bond = -1;  // -1: no intact bond
  double index = 0;        // its failure index f
  BreakMode mode = BreakMode::tensile;
};

// The bond's stress tensor: the mean of its two nodes' virial stresses (node_stress.h).
VoigtStress bond_stress_tensor(const std::vector<double>& node_stress, const Bond& bond);

// An affine path u(s) = at_zero + s per_unit of full displacements, in the search
// variable s = sign * lambda (so that compression reads like extension), and, when the
// reading needs them, the node stresses at s = 0 and per unit s.
struct PathStresses {
  Vector at_zero, per_unit;
  std::vector<double> stress_at_zero, stress_per_unit;
};

class FailureEvaluator {
 public:
  // Reads the model's per-bond moduli, lengths and strengths once.
  FailureEvaluator(std::shared_ptr<const FailureCriterion> criterion, BondStress reading,
                   const Model& model);
  // The same with the criterion of a [strength] section (make_criterion).
  FailureEvaluator(const Strength& strength, const Model& model);

  // f of every bond (0 for broken bonds) and the break mode of each.
  void evaluate(const Model& model, const Vector& displacement, std::vector<double>& index,
                std::vector<BreakMode>& mode) const;
  // f and the break mode of the given intact bonds only (one sweep for the node stresses
  // when the reading needs them, none over the other bonds' criteria).
  std::vector<CriticalBond> indices_of(const Model& model, const Vector& displacement,
                                       const std::vector<std::int64_t>& bonds) const;
  // The intact bond with the largest f; ties go to the lowest bond id.
  CriticalBond most_critical(const Model& model, const Vector& displacement) const;
  // The bonds tied for the largest f (within tie_tolerance relative), in bond-id order;
  // empty when that f is below `threshold`.
  std::vector<CriticalBond> critical_group(const Model& model, const Vector& displacement,
                                           double threshold) const;
  // Failure indices equal to this relative tolerance count as equal (docs/robustness.md).
  static constexpr double tie_tolerance = 1e-12;

  // The path u(lambda) = at_zero + lambda per_lambda in s = sign * lambda, with the node
  // stresses the reading needs.
  PathStresses path_stresses(const Model& model, const Vector& at_zero, const Vector& per_lambda,
                             double sign) const;
  // The smallest s in (from, to] at which bond b reaches f = 1 on the path; +infinity when
  // it does not. A crossing after needed_until cannot matter (docs: FailureCriterion): it
  // may be returned as +infinity (a bond that cannot reach 1 by then is not searched).
  double first_crossing(const Model& model, std::int64_t b, const PathStresses& path, double from,
                        double to, double needed_until) const;
  // Whether some intact bond may have f >= 1 at s on the path: f from the path's node
  // stresses at s is at least 1 - screen_margin. They differ from the stresses of the
  // state at that lambda (node_stresses) only by rounding, some 1e-13 of f, so every bond
  // that critical_group() finds at f >= 1 there passes; false means it finds none. Always
  // true on the strain reading, whose exact check costs no more.
  static constexpr double screen_margin = 1e-9;
  bool may_fail_at(const Model& model, const PathStresses& path, double s) const;

  // Whether bounds on a bond's stresses can rule out its crossing (may_cross_near): the
  // stress tensor resolved on the bond, with a criterion whose index does not fall as
  // sigma_n or tau grows.
  bool bounds_rule_out() const {
    return reading_ == Reading::resolved_tensor && criterion_->index_grows_with_stress();
  }
  // Bond b's normal and shear stress along the path, affine in s (the resolved-tensor and
  // strain readings).
  AffineBondStress affine_stress(const Model& model, std::int64_t b,
                                 const PathStresses& path) const;
  // Whether bond b may reach f = 1 somewhere in [from, until] on a path whose normal and
  // shear stress differ from `near` by at most `error` there (Pa). False rules a crossing
  // out; the same margin as the search's own skip. Needs bounds_rule_out().
  bool may_cross_near(const Model& model, std::int64_t b, const AffineBondStress& near,
                      double error, double from, double until) const;

  const FailureCriterion& criterion() const { return *criterion_; }
  const CriterionParameters& parameters() const { return criterion_->parameters(); }
  // True when f comes from the bonds' stress tensors (a tensor-only criterion, or
  // bond_stress = "tensor" or "critical_plane"), which need the node stresses.
  bool uses_tensor() const { return uses_tensor_; }
  BondStress bond_stress() const { return bond_stress_; }

 private:
  // Where f comes from: the criterion's tensor index, the tensor resolved on the bond
  // direction, or the bond's strains.
  enum class Reading { tensor_index, resolved_tensor, strain };
  FailureIndex bond_index(const Model& model, const Vector& displacement, std::int64_t bond,
                          const std::vector<double>& node_stress) const;
  BondStrength strength_of(const Model& model, std::int64_t bond) const {
    return {model.bond_sigma0[bond], model.bond_tau0[bond]};
  }
  // A quantity that grows with f and is cheap to compute (no square root), and the
  // relative tolerance in it that matches tie_tolerance in f.
  double rank(const Model& model, const Vector& displacement, std::int64_t bond,
              const std::vector<double>& node_stress) const;
  double rank_tolerance() const;
  std::shared_ptr<const FailureCriterion> criterion_;
  BondStress bond_stress_ = BondStress::strain;
  Reading reading_ = Reading::strain;
  bool uses_tensor_ = false;
  // Per bond: E / (L0 sigma0) and G / (L0 tau0), so that the normal and shear ratios are
  // dn times the first and |ds| times the second.
  std::vector<double> normal_scale_, shear_scale_;
};

}  // namespace latfrac
