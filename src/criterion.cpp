// Fracture criteria: failure index, break mode and the resolution of a [strength] section.
#include "latfrac/criterion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "latfrac/error.h"

namespace latfrac {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

double radians(double degrees) { return degrees * std::numbers::pi / 180; }

void require(bool condition, const std::string& message) {
  if (!condition) throw InputError("[strength] " + message);
}

bool needs_shear_strength(Criterion criterion) { return criterion != Criterion::tensile; }

}  // namespace

DruckerPragerConstants drucker_prager_constants(double friction_angle_deg, int dim) {
  const double psi = radians(friction_angle_deg);
  if (dim == 2) {
    const double t = std::tan(psi);
    const double root = std::sqrt(9 + 12 * t * t);
    return {t / root, 3 / root};
  }
  const double s = std::sin(psi);
  const double denominator = std::numbers::sqrt3 * (3 - s);
  return {2 * s / denominator, 6 * std::cos(psi) / denominator};
}

double derived_tau0(double sigma0, double friction_angle_deg, double factor_m) {
  const double psi = radians(friction_angle_deg);
  return factor_m * sigma0 * (1 + std::sin(psi)) / (2 * std::cos(psi));
}

CriterionParameters resolve_criterion(const Strength& strength, int dim) {
  if (dim != 2 && dim != 3) {
    throw InputError("[lattice] dim = " + std::to_string(dim) + ": allowed values are 2 and 3");
  }
  require(strength.sigma0 > 0, "sigma0 must be > 0 (Pa)");
  require(!strength.tau0 || *strength.tau0 > 0, "tau0 must be > 0 (Pa)");
  require(strength.tau0_factor > 0, "tau0_factor must be > 0");
  const auto& psi = strength.friction_angle;
  require(!psi || (*psi >= 0 && *psi < 90), "friction_angle must satisfy 0 <= psi < 90 (degrees)");
  require(!needs_shear_strength(strength.criterion) || strength.tau0 || psi,
          "criterion " + std::string(to_string(strength.criterion)) +
              " needs a shear strength: tau0 > 0 (Pa), or friction_angle (degrees) to derive it");
  require(strength.criterion != Criterion::drucker_prager || psi,
          "criterion drucker_prager needs friction_angle (degrees)");

  CriterionParameters p;
  p.criterion = strength.criterion;
  p.sigma0 = strength.sigma0;
  if (strength.tau0) {
    p.tau0 = *strength.tau0;
  } else if (psi) {
    p.tau0 = derived_tau0(strength.sigma0, *psi, strength.tau0_factor);
  } else {
    p.tau0 = infinity;
  }
  if (psi) {
    const DruckerPragerConstants dp = drucker_prager_constants(*psi, dim);
    p.dp_alpha = dp.alpha;
    p.dp_k_per_cohesion = dp.k_per_cohesion;
  } else {
    p.dp_alpha = p.dp_k_per_cohesion = std::numeric_limits<double>::quiet_NaN();
  }
  return p;
}

FailureIndex failure_index(Criterion criterion, double sigma_n, double tau, double sigma0,
                           double tau0) {
  const double normal = std::max(sigma_n, 0.0) / sigma0;
  const double shear = tau / tau0;
  const BreakMode larger = normal >= shear ? BreakMode::tensile : BreakMode::shear;
  switch (criterion) {
    case Criterion::tensile:
      return {normal, BreakMode::tensile};
    case Criterion::tensile_or_shear:
      return {std::max(normal, shear), larger};
    case Criterion::elliptic:
      return {normal * normal + shear * shear, larger};
    case Criterion::drucker_prager:
      break;
  }
  throw Error(
      "failure_index: drucker_prager needs the bond's stress tensor (drucker_prager_index)");
}

ResolvedStress resolve_on(const VoigtStress& s, const Eigen::Vector3d& n) {
  // Voigt xx, yy, zz, yz, xz, xy.
  const Eigen::Vector3d traction(s[0] * n.x() + s[5] * n.y() + s[4] * n.z(),
                                 s[5] * n.x() + s[1] * n.y() + s[3] * n.z(),
                                 s[4] * n.x() + s[3] * n.y() + s[2] * n.z());
  ResolvedStress r;
  r.normal = n.dot(traction);
  r.shear = traction - r.normal * n;
  return r;
}

double first_invariant(const VoigtStress& s) { return s[0] + s[1] + s[2]; }

double j2_product(const VoigtStress& a, const VoigtStress& b) {
  const double normal =
      (a[0] - a[1]) * (b[0] - b[1]) + (a[1] - a[2]) * (b[1] - b[2]) + (a[2] - a[0]) * (b[2] - b[0]);
  return normal / 6 + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
}

FailureIndex drucker_prager_index(const VoigtStress& stress, double alpha, double k) {
  const double deviatoric = std::sqrt(second_deviatoric_invariant(stress));
  const double mean = alpha * first_invariant(stress);
  return {(deviatoric + mean) / k, mean >= deviatoric ? BreakMode::tensile : BreakMode::shear};
}

}  // namespace latfrac
