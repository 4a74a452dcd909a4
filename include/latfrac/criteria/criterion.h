// Fracture criteria: the failure index f of a bond (it breaks when f >= 1) and its mode.
//
// With <x>+ = max(x, 0), sigma_n the bond's normal stress (tension positive) and tau >= 0
// its shear stress (model.md section 4, docs/criteria.md):
//   tensile           f = <sigma_n>+ / sigma0
//   tensile_or_shear  f = max(<sigma_n>+ / sigma0, tau / tau0)
//   elliptic          f = (<sigma_n>+ / sigma0)^2 + (tau / tau0)^2   (the paper's Eq. 3)
//   drucker_prager    f = (sqrt(J2) + alpha I1) / k on the bond's stress tensor
// Compression never drives failure in the first three. The mode is tensile when the
// normal part is the larger part of f, shear otherwise; for Drucker-Prager it is tensile
// when the mean-stress term alpha I1 is at least sqrt(J2).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "latfrac/criteria/strength.h"

namespace latfrac {

enum class BreakMode : std::int8_t { tensile = 0, shear = 1, precut = 2 };

struct FailureIndex {
  double value = 0;
  BreakMode mode = BreakMode::tensile;
};

// Voigt order xx, yy, zz, yz, xz, xy (Pa, tension positive).
using VoigtStress = std::array<double, 6>;

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
  double sigma0 = 0;  // Pa
  // Pa: given, or derived from the friction angle; +inf when neither is given (only the
  // tensile criterion allows that).
  double tau0 = 0;
  // Drucker-Prager constants (the cohesion c is the bond's tau0); NaN without a friction angle.
  double dp_alpha = 0;
  double dp_k_per_cohesion = 0;
};

// dim (2 or 3) selects the plane-strain or 3-D Drucker-Prager constants. Throws InputError
// when the criterion needs a strength the section does not give, or a value is out of range.
CriterionParameters resolve_criterion(const Strength& strength, int dim);

// Mohr-Coulomb shear cohesion from the tensile strength: m sigma0 (1 + sin psi) / (2 cos psi).
double derived_tau0(double sigma0, double friction_angle_deg, double factor_m);

// Stress-based indices from sigma_n = E eps_n and tau = G gamma (Pa) with the bond's own
// strengths. tau0 may be +inf (no shear failure). Drucker-Prager is not one of these:
// it needs the stress tensor (drucker_prager_index); passing it throws Error.
FailureIndex failure_index(Criterion criterion, double sigma_n, double tau, double sigma0,
                           double tau0);

// Drucker-Prager on the bond's stress tensor; in 2-D, yy is already nu (xx + zz).
// k = k_per_cohesion * c.
FailureIndex drucker_prager_index(const VoigtStress& stress, double alpha, double k);

// A stress tensor resolved on the unit direction n: the normal stress n.S.n and the shear
// traction vector S n - (n.S.n) n (Pa, tension positive). Linear in S.
struct ResolvedStress {
  double normal = 0;
  Eigen::Vector3d shear = Eigen::Vector3d::Zero();
};
ResolvedStress resolve_on(const VoigtStress& stress, const Eigen::Vector3d& n);

// The largest f over all planes through the point (bond_stress = "critical_plane"), from
// the outer Mohr circle: centre c = (s1 + s3) / 2, radius r = (s1 - s3) / 2 with s1 >= s3
// the extreme principal stresses (in 3-D of the full tensor; in 2-D of the x-z part, the
// planes that contain the y axis). A plane whose normal makes the angle phi / 2 with s1
// carries sigma_n = c + r cos phi and tau = r sin phi, and every criterion here grows
// with <sigma_n>+ and tau, so its largest value over all planes lies on that circle:
//   tensile           f = <s1>+ / sigma0                       (Rankine)
//   tensile_or_shear  f = max(<s1>+ / sigma0, r / tau0)        (Rankine or Tresca)
//   elliptic          f = max over phi of (<c + r cos phi>+ / sigma0)^2 + (r sin phi / tau0)^2
// The mode is that of the maximising plane. drucker_prager throws Error (it is already a
// function of the tensor's invariants: drucker_prager_index).
FailureIndex critical_plane_index(Criterion criterion, const VoigtStress& stress, int dim,
                                  double sigma0, double tau0);

// I1 = trace.
double first_invariant(const VoigtStress& stress);
// The symmetric bilinear form whose diagonal is J2: (s_a : s_b) / 2 with s the deviators,
// Voigt shear components counted twice. Written with differences of normal components so
// that a large mean stress does not cancel against the deviator.
double j2_product(const VoigtStress& a, const VoigtStress& b);
inline double second_deviatoric_invariant(const VoigtStress& s) { return j2_product(s, s); }

}  // namespace latfrac
