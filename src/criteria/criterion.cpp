// The registry of criteria, the factory, and the resolution of a [strength] section.
#include "latfrac/criteria/criterion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "criterion_makers.h"
#include "latfrac/base/error.h"

namespace latfrac {
namespace {

// One criterion a problem file can name.
struct CriterionEntry {
  Criterion criterion;
  const char* name;
  bool needs_shear_strength;  // tau0, or a friction angle to derive it
  bool needs_friction_angle;  // a friction angle of its own
  std::unique_ptr<FailureCriterion> (*make)(const CriterionParameters&);
};

// Every criterion, in the order of the Criterion enumeration.
constexpr CriterionEntry registry[] = {
    {Criterion::tensile, "tensile", false, false, make_tensile},
    {Criterion::tensile_or_shear, "tensile_or_shear", true, false, make_tensile_or_shear},
    {Criterion::elliptic, "elliptic", true, false, make_elliptic},
    {Criterion::drucker_prager, "drucker_prager", false, true, make_drucker_prager},
};

const CriterionEntry& entry_of(Criterion criterion) {
  for (const CriterionEntry& entry : registry) {
    if (entry.criterion == criterion) return entry;
  }
  throw Error("no criterion is registered as number " +
              std::to_string(static_cast<int>(criterion)) + " (src/criteria/criterion.cpp)");
}

constexpr double infinity = std::numeric_limits<double>::infinity();

double radians(double degrees) { return degrees * std::numbers::pi / 180; }

void require(bool condition, const std::string& message) {
  if (!condition) throw InputError("[strength] " + message);
}

}  // namespace

const char* to_string(Criterion criterion) { return entry_of(criterion).name; }

const std::vector<std::string>& criterion_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const CriterionEntry& entry : registry) list.push_back(entry.name);
    return list;
  }();
  return names;
}

bool needs_shear_strength(Criterion criterion) { return entry_of(criterion).needs_shear_strength; }
bool needs_friction_angle(Criterion criterion) { return entry_of(criterion).needs_friction_angle; }

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
  const CriterionEntry& entry = entry_of(strength.criterion);
  require(strength.sigma0 > 0, "sigma0 must be > 0 (Pa)");
  require(!strength.tau0 || *strength.tau0 > 0, "tau0 must be > 0 (Pa)");
  require(strength.tau0_factor > 0, "tau0_factor must be > 0");
  const auto& psi = strength.friction_angle;
  require(!psi || (*psi >= 0 && *psi < 90), "friction_angle must satisfy 0 <= psi < 90 (degrees)");
  require(!entry.needs_shear_strength || strength.tau0 || psi,
          "criterion " + std::string(entry.name) +
              " needs a shear strength: tau0 > 0 (Pa), or friction_angle (degrees) to derive it");
  require(!entry.needs_friction_angle || psi,
          "criterion " + std::string(entry.name) + " needs friction_angle (degrees)");
  require(std::isfinite(strength.internal_friction) && strength.internal_friction >= 0,
          "internal_friction must be >= 0 (dimensionless)");
  require(!(strength.internal_friction > 0 && strength.criterion == Criterion::elliptic &&
            strength.bond_stress == BondStress::critical_plane),
          "internal_friction with criterion elliptic is not available on bond_stress = "
          "\"critical_plane\" (its largest value over planes has no convex form); use "
          "bond_stress = \"tensor\" or \"strain\", or criterion tensile_or_shear");
  require(!(strength.internal_friction > 0 && (strength.criterion == Criterion::tensile ||
                                               strength.criterion == Criterion::drucker_prager)),
          "internal_friction is not used by criterion " + std::string(entry.name) +
              " (tensile has no shear strength; drucker_prager has its own pressure term)");

  CriterionParameters p;
  p.criterion = strength.criterion;
  p.dim = dim;
  p.internal_friction = strength.internal_friction;
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

std::shared_ptr<const FailureCriterion> make_criterion(const Strength& strength, int dim) {
  const CriterionParameters parameters = resolve_criterion(strength, dim);
  return entry_of(parameters.criterion).make(parameters);
}

double FailureCriterion::first_tensor_crossing(const VoigtStress& s0, const VoigtStress& s1,
                                               const BondStrength& strength, double from,
                                               double to, double needed_until) const {
  const auto f = [&](double l) {
    VoigtStress at;
    for (int k = 0; k < 6; ++k) at[k] = s0[k] + l * s1[k];
    return tensor_index(at, strength).value;
  };
  // A convex f below 1 at `from` and at `needed_until` stays below 1 between them: no
  // crossing that matters. Otherwise the bisection runs on [from, to] whatever
  // needed_until is, so a bond's crossing does not depend on the bonds searched before it
  // (the same on any number of threads).
  const double until = std::min(to, needed_until);
  if (until < to && until > from && f(from) < 1 && f(until) < 1)
    return std::numeric_limits<double>::infinity();
  return first_crossing_convex(f, from, to);
}

}  // namespace latfrac
