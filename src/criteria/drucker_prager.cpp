// The Drucker-Prager criterion on the bond's stress tensor, and its closed-form crossing.
#include "latfrac/criteria/drucker_prager.h"

#include <cmath>

#include "criterion_makers.h"
#include "crossing_parts.h"
#include "latfrac/base/error.h"

namespace latfrac {
namespace {

using namespace crossing_parts;

// Near r = 0 both square-root branches meet; a root with r this small (relative to its
// terms) is on the admissible branch within rounding.
constexpr double branch_tolerance = 1e-9;

// Squaring makes two roots of J2 - r^2 nearly coincide on near-hydrostatic paths, which
// costs up to half the digits (about 1e-8 relative). Newton steps on the unsquared
// phi(x) = sqrt(J2(x)) - r(x), whose slope at the crossing is positive (f is convex and
// rises through 1), restore full precision; a step is kept only when it reduces |phi|.
double polished(const VoigtStress& start, const VoigtStress& slope, double r0, double r1, double x,
                double length) {
  const auto phi = [&](double at, double* derivative) {
    VoigtStress s;
    for (int i = 0; i < 6; ++i) s[i] = start[i] + at * slope[i];
    const double deviatoric = std::sqrt(second_deviatoric_invariant(s));
    if (derivative) *derivative = j2_product(s, slope) / deviatoric - r1;
    return deviatoric - (r0 + r1 * at);
  };
  for (int step = 0; step < 2; ++step) {
    double derivative = 0;
    const double residual = phi(x, &derivative);
    if (residual == 0 || !(derivative > 0)) break;
    const double next = x - residual / derivative;
    if (!(next > 0 && next <= length) || std::abs(phi(next, nullptr)) >= std::abs(residual)) break;
    x = next;
  }
  return x;
}

// The tensor is all there is: the bond-stress readings do not apply, and the cohesion c
// of k = k_per_cohesion c is the bond's tau0.
class DruckerPrager final : public FailureCriterion {
 public:
  using FailureCriterion::FailureCriterion;

  FailureIndex index(double, double, const BondStrength&) const override {
    throw Error("drucker_prager needs the bond's stress tensor, not its normal and shear stress");
  }

  FailureIndex tensor_index(const VoigtStress& stress, const BondStrength& strength) const override {
    return drucker_prager_index(stress, parameters().dp_alpha, k(strength));
  }

  double first_crossing(const AffineBondStress&, const BondStrength&, double, double) const override {
    throw Error("drucker_prager needs the bond's stress tensor (first_tensor_crossing)");
  }

  // Closed form: needed_until does not shorten it.
  double first_tensor_crossing(const VoigtStress& s0, const VoigtStress& s1,
                               const BondStrength& strength, double from, double to,
                               double) const override {
    return first_crossing_drucker_prager(s0, s1, parameters().dp_alpha, k(strength), from, to);
  }

  double rank(double, double) const override {
    throw Error("drucker_prager ranks bonds on their stress tensors");
  }

  bool tensor_only() const override { return true; }

 private:
  double k(const BondStrength& strength) const {
    return parameters().dp_k_per_cohesion * strength.tau0;
  }
};

}  // namespace

FailureIndex drucker_prager_index(const VoigtStress& stress, double alpha, double k) {
  const double deviatoric = std::sqrt(second_deviatoric_invariant(stress));
  const double mean = alpha * first_invariant(stress);
  return {(deviatoric + mean) / k, mean >= deviatoric ? BreakMode::tensile : BreakMode::shear};
}

// sqrt(J2(x)) = r(x) with r = k - alpha I1, squared: J2(x) - r(x)^2 = 0. The square admits
// roots of sqrt(J2) = -r as well; those lie where alpha I1 > k, i.e. f > 1, and are dropped.
double first_crossing_drucker_prager(const VoigtStress& s0, const VoigtStress& s1, double alpha,
                                     double k, double from, double to) {
  VoigtStress start;
  for (int i = 0; i < 6; ++i) start[i] = s0[i] + from * s1[i];
  if (drucker_prager_index(start, alpha, k).value >= 1) return from;
  const double r0 = k - alpha * first_invariant(start);
  const double r1 = -alpha * first_invariant(s1);
  const Quadratic g{second_deviatoric_invariant(s1) - r1 * r1,
                    2 * (j2_product(start, s1) - r0 * r1),
                    second_deviatoric_invariant(start) - r0 * r0};
  const auto admissible = [&](double x) {
    return r0 + r1 * x >= -branch_tolerance * (std::abs(r0) + std::abs(r1 * x));
  };
  const double length = to - from;
  double x = first_nonnegative(g, length, admissible);
  if (x > 0 && x < infinity) x = polished(start, s1, r0, r1, x, length);
  return to_lambda(from, x, to);
}

std::unique_ptr<FailureCriterion> make_drucker_prager(const CriterionParameters& parameters) {
  return std::make_unique<DruckerPrager>(parameters);
}

}  // namespace latfrac
