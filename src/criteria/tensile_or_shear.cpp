// The tensile-or-shear criterion: f = max(<sigma_n>+ / sigma0, tau / (tau0 + mu_i <-sigma_n>+))
// (critical plane: Rankine or Tresca; with internal friction, Rankine or Mohr-Coulomb).
#include <algorithm>
#include <cmath>

#include "criterion_makers.h"
#include "crossing_parts.h"
#include "mohr_circle.h"

namespace latfrac {
namespace {

using namespace crossing_parts;

FailureIndex larger_of(double normal, double shear) {
  return {std::max(normal, shear), normal >= shear ? BreakMode::tensile : BreakMode::shear};
}

class TensileOrShear final : public FailureCriterion {
 public:
  using FailureCriterion::FailureCriterion;

  FailureIndex index(double sigma_n, double tau, const BondStrength& strength) const override {
    return larger_of(std::max(sigma_n, 0.0) / strength.sigma0,
                     tau / (strength.tau0 + mu() * std::max(-sigma_n, 0.0)));
  }

  // The largest normal stress (s1) and, without internal friction, the largest shear
  // stress (the circle's radius): Tresca. With it, Mohr-Coulomb: the circle reaches the
  // line tau = tau0 - mu_i sigma_n where r sqrt(1 + mu_i^2) + mu_i c = tau0, so the shear
  // part is (r sqrt(1 + mu_i^2) + mu_i c) / tau0, linear in (c, r), hence convex along a
  // path (docs/criteria.md: on the critical plane the line is not capped at tau0 in
  // tension, where the tension branch usually decides first).
  FailureIndex tensor_index(const VoigtStress& stress, const BondStrength& strength) const override {
    const MohrCircle circle = outer_circle(stress, dim());
    const double normal = std::max(circle.centre + circle.radius, 0.0) / strength.sigma0;
    if (mu() == 0) return larger_of(normal, circle.radius / strength.tau0);
    return larger_of(normal, (circle.radius * std::sqrt(1 + mu() * mu()) + mu() * circle.centre) /
                                 strength.tau0);
  }

  // The earlier of the two parts' crossings.
  double first_crossing(const AffineBondStress& stress, const BondStrength& strength, double from,
                        double to) const override {
    const AffineBondStress start = moved_to(stress, from);
    if (index(start.normal0, start.shear0.norm(), strength).value >= 1) return from;
    const double length = to - from;
    const double x = std::min(first_nonnegative(tensile_part(start, strength.sigma0), length),
                              first_shear_crossing(start, strength.tau0, mu(), length));
    return to_lambda(from, x, to);
  }

  // The larger squared ratio (the shear ratio with the strength the evaluator gives it).
  // <sigma_n>+ and tau raise f, and the strength tau0 + mu_i <-sigma_n>+ falls as sigma_n
  // grows.
  bool index_grows_with_stress() const override { return true; }

  double rank(double normal_ratio, double shear_ratio_squared) const override {
    return std::max(normal_ratio * normal_ratio, shear_ratio_squared);
  }

 private:
  double mu() const { return parameters().internal_friction; }
};

}  // namespace

std::unique_ptr<FailureCriterion> make_tensile_or_shear(const CriterionParameters& parameters) {
  return std::make_unique<TensileOrShear>(parameters);
}

}  // namespace latfrac
