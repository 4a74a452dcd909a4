// Failure indices of every intact bond: which bond breaks next, and how.
//
// A bond's normal and shear stresses come from its strains and its layer's moduli,
// sigma_n = E dn / L0 and tau = G |ds| / L0 (model.md section 2); Drucker-Prager uses the
// bond's stress tensor, the mean of its two nodes' virial stresses. The criteria
// themselves are in criterion.h.
#pragma once

#include <cstdint>
#include <vector>

#include "latfrac/criterion.h"
#include "latfrac/model.h"

namespace latfrac {

struct CriticalBond {
  std::int64_t bond = -1;  // -1: no intact bond
  double index = 0;        // its failure index f
  BreakMode mode = BreakMode::tensile;
};

class FailureEvaluator {
 public:
  // Reads the model's per-bond moduli, lengths and strengths once.
  FailureEvaluator(const Strength& strength, const Model& model);

  // f of every bond (0 for broken bonds) and the break mode of each.
  void evaluate(const Model& model, const Vector& displacement, std::vector<double>& index,
                std::vector<BreakMode>& mode) const;
  // The intact bond with the largest f; ties go to the lowest bond id.
  CriticalBond most_critical(const Model& model, const Vector& displacement) const;

  const CriterionParameters& parameters() const { return parameters_; }

 private:
  FailureIndex bond_index(const Model& model, const Vector& displacement, std::int64_t bond,
                          const std::vector<double>& node_stress) const;
  CriterionParameters parameters_;
  // Per bond: E / (L0 sigma0) and G / (L0 tau0), so that the normal and shear ratios are
  // dn times the first and |ds| times the second.
  std::vector<double> normal_scale_, shear_scale_;
};

}  // namespace latfrac
