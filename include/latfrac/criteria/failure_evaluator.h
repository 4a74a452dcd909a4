// Failure indices of every intact bond: which bond breaks next, and how.
//
// A bond's normal and shear stresses come from its strains and its layer's moduli,
// sigma_n = E dn / L0 and tau = G |ds| / L0 (model.md section 2), or, with
// bond_stress = "tensor", from the bond's stress tensor resolved on its direction, or,
// with bond_stress = "critical_plane", from that tensor on the plane where f is largest.
// Drucker-Prager always uses that tensor, the mean of the two nodes' virial stresses.
// The criteria themselves are in criterion.h.
#pragma once

#include <cstdint>
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

class FailureEvaluator {
 public:
  // Reads the model's per-bond moduli, lengths and strengths once.
  FailureEvaluator(const Strength& strength, const Model& model);

  // f of every bond (0 for broken bonds) and the break mode of each.
  void evaluate(const Model& model, const Vector& displacement, std::vector<double>& index,
                std::vector<BreakMode>& mode) const;
  // The intact bond with the largest f; ties go to the lowest bond id.
  CriticalBond most_critical(const Model& model, const Vector& displacement) const;
  // The bonds tied for the largest f (within tie_tolerance relative), in bond-id order;
  // empty when that f is below `threshold`.
  std::vector<CriticalBond> critical_group(const Model& model, const Vector& displacement,
                                           double threshold) const;
  // Failure indices equal to this relative tolerance count as equal (docs/robustness.md).
  static constexpr double tie_tolerance = 1e-12;

  const CriterionParameters& parameters() const { return parameters_; }
  // True when f comes from the bonds' stress tensors (Drucker-Prager, or bond_stress =
  // "tensor" or "critical_plane"), which need the node stresses.
  bool uses_tensor() const { return uses_tensor_; }
  BondStress bond_stress() const { return bond_stress_; }

 private:
  FailureIndex bond_index(const Model& model, const Vector& displacement, std::int64_t bond,
                          const std::vector<double>& node_stress) const;
  // A quantity that grows with f and is cheap to compute (no square root), and the
  // relative tolerance in it that matches tie_tolerance in f.
  double rank(const Model& model, const Vector& displacement, std::int64_t bond,
              const std::vector<double>& node_stress) const;
  double rank_tolerance() const;
  CriterionParameters parameters_;
  BondStress bond_stress_ = BondStress::strain;
  bool uses_tensor_ = false;
  // Per bond: E / (L0 sigma0) and G / (L0 tau0), so that the normal and shear ratios are
  // dn times the first and |ds| times the second.
  std::vector<double> normal_scale_, shear_scale_;
};

}  // namespace latfrac
