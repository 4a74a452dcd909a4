// Fracture criteria: failure index, break mode and the resolution of a [strength] section.
#include "latfrac/criteria/criterion.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "latfrac/base/error.h"

namespace latfrac {

const char* to_string(Criterion criterion) {
  switch (criterion) {
    case Criterion::tensile:
      return "tensile";
    case Criterion::tensile_or_shear:
      return "tensile_or_shear";
    case Criterion::elliptic:
      return "elliptic";
    case Criterion::drucker_prager:
      return "drucker_prager";
  }
  return "unknown";
}

const char* to_string(BondStress source) {
  switch (source) {
    case BondStress::strain:
      return "strain";
    case BondStress::tensor:
      return "tensor";
    case BondStress::critical_plane:
      return "critical_plane";
  }
  return "unknown";
}

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

namespace {

// Centre and radius of the outer Mohr circle (Pa).
struct MohrCircle {
  double centre = 0, radius = 0;
};

MohrCircle outer_circle(const VoigtStress& s, int dim) {
  if (dim == 2) {
    return {0.5 * (s[0] + s[2]), std::hypot(0.5 * (s[0] - s[2]), s[4])};
  }
  Eigen::Matrix3d m;
  m << s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2];
  const Eigen::Vector3d principal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues();
  return {0.5 * (principal(2) + principal(0)), 0.5 * (principal(2) - principal(0))};
}

// The elliptic f on the plane with cos phi = x, and its parts.
struct EllipticParts {
  double normal = 0, shear = 0;  // (<sigma_n>+ / sigma0)^2 and (tau / tau0)^2
  double value() const { return normal + shear; }
};

EllipticParts elliptic_on_circle(const MohrCircle& circle, double x, double sigma0, double tau0) {
  const double normal = std::max(circle.centre + circle.radius * x, 0.0) / sigma0;
  const double shear_squared = circle.radius * circle.radius * std::max(1 - x * x, 0.0);
  return {normal * normal, shear_squared / (tau0 * tau0)};
}

// g(x) = <c + r x>+^2 / sigma0^2 + r^2 (1 - x^2) / tau0^2 on [-1, 1] is a quadratic on
// each side of the kink x = -c / r, so its maximum lies at an end, at the kink, at x = 0
// (the stationary point where the normal part is 0) or at the stationary point of the
// tensile piece, x = c tau0^2 / (r (sigma0^2 - tau0^2)).
EllipticParts elliptic_maximum(const MohrCircle& circle, double sigma0, double tau0) {
  const double c = circle.centre, r = circle.radius;
  std::vector<double> candidates = {-1.0, 0.0, 1.0};
  if (r > 0) {
    candidates.push_back(-c / r);
    const double a = sigma0 * sigma0, b = tau0 * tau0;
    if (a != b && std::isfinite(b)) candidates.push_back(c * b / (r * (a - b)));
  }
  EllipticParts best;
  for (double x : candidates) {
    if (!std::isfinite(x)) continue;
    const EllipticParts parts = elliptic_on_circle(circle, std::clamp(x, -1.0, 1.0), sigma0, tau0);
    if (parts.value() > best.value()) best = parts;
  }
  return best;
}

}  // namespace

FailureIndex critical_plane_index(Criterion criterion, const VoigtStress& stress, int dim,
                                  double sigma0, double tau0) {
  const MohrCircle circle = outer_circle(stress, dim);
  const double normal = std::max(circle.centre + circle.radius, 0.0) / sigma0;
  const double shear = circle.radius / tau0;
  switch (criterion) {
    case Criterion::tensile:
      return {normal, BreakMode::tensile};
    case Criterion::tensile_or_shear:
      return {std::max(normal, shear), normal >= shear ? BreakMode::tensile : BreakMode::shear};
    case Criterion::elliptic: {
      const EllipticParts parts = elliptic_maximum(circle, sigma0, tau0);
      return {parts.value(),
              parts.normal >= parts.shear ? BreakMode::tensile : BreakMode::shear};
    }
    case Criterion::drucker_prager:
      break;
  }
  throw Error(
      "critical_plane_index: drucker_prager is a function of the tensor's invariants "
      "(drucker_prager_index)");
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
