// Fracture criteria behind one interface: a bond's failure index f (it breaks when f >= 1),
// its mode, and the exact lambda at which f reaches 1 on an affine path.
//
// With <x>+ = max(x, 0), sigma_n a bond's normal stress (tension positive) and tau >= 0
// its shear stress (model.md section 4, docs/criteria.md):
//   tensile           f = <sigma_n>+ / sigma0                          (tensile.cpp)
//   tensile_or_shear  f = max(<sigma_n>+ / sigma0, tau / tau0)         (tensile_or_shear.cpp)
//   elliptic          f = (<sigma_n>+ / sigma0)^2 + (tau / tau0)^2     (elliptic.cpp; the paper's Eq. 3)
//   drucker_prager    f = (sqrt(J2) + alpha I1) / k on the stress tensor (drucker_prager.cpp)
// Compression never drives failure in the first three. The mode is tensile when the
// normal part is the larger part of f, shear otherwise; for Drucker-Prager it is tensile
// when the mean-stress term alpha I1 is at least sqrt(J2).
//
// Adding a criterion: a class implementing FailureCriterion in its own file, a value in
// the Criterion enumeration (strength.h), and one entry in the registry (criterion.cpp).
// make_criterion refuses a criterion without an entry; nothing falls back to another.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "latfrac/criteria/crossing.h"
#include "latfrac/criteria/strength.h"
#include "latfrac/criteria/stress.h"

namespace latfrac {

// A bond's strengths, Pa: tensile strength sigma0 and shear cohesion tau0 (+inf: none).
struct BondStrength {
  double sigma0 = 0;
  double tau0 = 0;
};

// Drucker-Prager constants for f = (sqrt(J2) + alpha I1) / (k_per_cohesion * c).
//   3-D, matched to Mohr-Coulomb on the compression meridian:
//     alpha = 2 sin psi / (sqrt3 (3 - sin psi)),  k = 6 c cos psi / (sqrt3 (3 - sin psi))
//   2-D plane strain, matched to Mohr-Coulomb under plane-strain plastic flow:
//     alpha = tan psi / sqrt(9 + 12 tan^2 psi),   k = 3 c / sqrt(9 + 12 tan^2 psi)
struct DruckerPragerConstants {
  double alpha = 0;
  double k_per_cohesion = 0;
};
DruckerPragerConstants drucker_prager_constants(double friction_angle_deg, int dim);

// Resolved strengths and Drucker-Prager constants of a scene's [strength] section.
struct CriterionParameters {
  Criterion criterion = Criterion::elliptic;
  int dim = 2;
  double sigma0 = 0;  // Pa
  // Pa: given, or derived from the friction angle; +inf when neither is given (only the
  // tensile criterion allows that).
  double tau0 = 0;
  // Drucker-Prager constants (the cohesion c is the bond's tau0); NaN without a friction angle.
  double dp_alpha = 0;
  double dp_k_per_cohesion = 0;
  // mu_i of tau0 + mu_i <-sigma_n>+ (dimensionless, >= 0).
  double internal_friction = 0;
};

// dim (2 or 3) selects the plane-strain or 3-D Drucker-Prager constants. Throws InputError
// when the criterion needs a strength the section does not give, or a value is out of range.
CriterionParameters resolve_criterion(const Strength& strength, int dim);

// Mohr-Coulomb shear cohesion from the tensile strength: m sigma0 (1 + sin psi) / (2 cos psi).
double derived_tau0(double sigma0, double friction_angle_deg, double factor_m);

class FailureCriterion {
 public:
  explicit FailureCriterion(const CriterionParameters& parameters) : parameters_(parameters) {}
  virtual ~FailureCriterion() = default;

  // f from a bond's normal stress sigma_n and shear stress tau (the strain and tensor
  // readings). Throws Error for a criterion that only a stress tensor defines.
  virtual FailureIndex index(double sigma_n, double tau, const BondStrength& strength) const = 0;
  // f of a stress tensor: the largest f over all planes through the point (the
  // critical-plane reading), or the criterion's own function of the invariants.
  virtual FailureIndex tensor_index(const VoigtStress& stress,
                                    const BondStrength& strength) const = 0;
  // The smallest l in (from, to] with index() >= 1 on sigma_n and the shear vector affine
  // in l; `from` itself when f(from) >= 1; +infinity when f stays below 1.
  virtual double first_crossing(const AffineBondStress& stress, const BondStrength& strength,
                                double from, double to) const = 0;
  // The same for tensor_index() on S(l) = s0 + l s1. By default bisection on the convex f;
  // a crossing later than `needed_until` cannot matter to the caller (a later bond cannot
  // come first), so a bond below 1 there is not bisected. The crossing found does not
  // depend on needed_until.
  virtual double first_tensor_crossing(const VoigtStress& s0, const VoigtStress& s1,
                                       const BondStrength& strength, double from, double to,
                                       double needed_until) const;
  // A quantity that grows with index() on the strain reading, cheap to compute (no square
  // root), from the normal ratio <sigma_n>+ / sigma0 and the squared shear ratio
  // (tau / tau0)^2; ranks bonds in the hot loop of every cascade.
  virtual double rank(double normal_ratio, double shear_ratio_squared) const = 0;
  // True when only the stress tensor defines f (the bond-stress readings do not apply).
  virtual bool tensor_only() const { return false; }
  // True when index() does not decrease as sigma_n or tau grows (more tension, less
  // compression, more shear). Then on an affine path f(l) <= index(the larger sigma_n of
  // the interval's ends, the larger |tau| of its ends): sigma_n is affine and |tau| convex,
  // so both peak at an end. The crossing search uses it to skip bonds that cannot reach 1.
  virtual bool index_grows_with_stress() const { return false; }

  const CriterionParameters& parameters() const { return parameters_; }
  int dim() const { return parameters_.dim; }

 private:
  CriterionParameters parameters_;
};

// The criterion of a [strength] section, its strengths resolved once (resolve_criterion).
std::shared_ptr<const FailureCriterion> make_criterion(const Strength& strength, int dim);

// The names a problem file may give, in the order of the Criterion enumeration.
const std::vector<std::string>& criterion_names();
// Whether a criterion needs a shear strength (tau0, or a friction angle to derive it) and
// a friction angle of its own.
bool needs_shear_strength(Criterion criterion);
bool needs_friction_angle(Criterion criterion);

}  // namespace latfrac
